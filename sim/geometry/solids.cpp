#include "sim/geometry/solids.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "sim/core/error.h"

namespace spume {
namespace {

// The gap between |x| and the next float up.
float ulp_of(float x) {
  x = std::abs(x);
  return std::nextafter(x, std::numeric_limits<float>::infinity()) - x;
}

// Float positions are spaced by an ulp of their largest coordinate: 1e-4 r (2 um at r = 21 mm) is
// below half of it beyond about 1,700 r from the origin (35 m), so a point set to "surface plus skin"
// would round back onto the surface or an ulp inside. Far out the skin grows to a few ulps of p,
// which rounding (up to an ulp or two where a box's centre is rounded) cannot undo.
constexpr float kSkinUlps = 4.0f;
float representable_skin(const Vec3f& p, float skin) {
  return std::max(skin, kSkinUlps * ulp_of(p.cwiseAbs().maxCoeff()));
}

// Signed distance to a box's surface, positive outside, with the outward normal of the nearest face.
float box_distance(const Vec3f& p, const Vec3f& lo, const Vec3f& hi, Vec3f& normal) {
  const Vec3f centre = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
  const Vec3f q = (p - centre).cwiseAbs() - half;
  const Vec3f outside = q.cwiseMax(0.0f);
  if (outside.squaredNorm() > 0.0f) {
    const Vec3f nearest = p.cwiseMax(lo).cwiseMin(hi);
    normal = (p - nearest).normalized();
    return outside.norm();
  }
  int axis = 0;
  q.maxCoeff(&axis);  // the face we are closest to from inside
  normal = Vec3f::Zero();
  normal[axis] = p[axis] >= centre[axis] ? 1.0f : -1.0f;
  return q[axis];
}

// box_distance in the box's own frame for a rotated box (normal turned back into the world).
float oriented_box_distance(const Solid& s, const Vec3f& p, Vec3f& normal) {
  if (!s.rotated()) return box_distance(p, s.min, s.max, normal);
  const Vec3f c = s.centre();
  const Vec3f local = c + s.orientation.conjugate() * (p - c);
  Vec3f n;
  const float d = box_distance(local, s.min, s.max, n);
  normal = s.orientation * n;
  return d;
}

// Above an open tank's rim a point passes over the side walls (axes other than up).
bool above_open_walls(const Solid& tank, const Vec3f& p, int axis) {
  return tank.open_top && axis != tank.up_axis && p[tank.up_axis] > tank.max[tank.up_axis];
}

// Whether p, beyond the tank's wall of `axis` (low side or high), is inside that wall: within its
// thickness, and within the walls' outer extent along the other axes. Farther out is the world
// outside the tank (spray thrown over the rim falls there; it is not pulled back in through the wall).
bool in_wall_slab(const Solid& tank, const Vec3f& p, int axis, bool low) {
  const float t = tank.wall_thickness;
  const float depth = low ? tank.min[axis] - p[axis] : p[axis] - tank.max[axis];
  if (!(depth > 0.0f) || !(depth < t)) return false;
  for (int b = 0; b < 3; ++b) {
    if (b == axis) continue;
    if (p[b] < tank.min[b] - t) return false;
    const bool has_top = !(tank.open_top && b == tank.up_axis);
    if (p[b] > tank.max[b] + (has_top ? t : 0.0f)) return false;
  }
  return true;
}

// p lies inside the solid (for a tank: beyond its walls), with no tolerance.
bool contains(const Solid& s, const Vec3f& p) {
  switch (s.kind) {
    case Solid::Kind::Tank:
      for (int a = 0; a < 3; ++a) {
        if (above_open_walls(s, p, a)) continue;
        if (in_wall_slab(s, p, a, true)) return true;
        if (!(s.open_top && a == s.up_axis) && in_wall_slab(s, p, a, false)) return true;
      }
      return false;
    case Solid::Kind::Box: {
      Vec3f n;
      return oriented_box_distance(s, p, n) < 0.0f;
    }
    case Solid::Kind::Sphere:
      return (p - s.center).squaredNorm() < s.radius * s.radius;
  }
  return false;
}

}  // namespace

Vec3f Motion::offset(double t) const {
  switch (kind) {
    case Kind::None:
      break;
    case Kind::Keyframes: {
      if (times.empty()) break;
      if (t <= times.front()) return offsets.front();
      if (t >= times.back()) return offsets.back();
      const size_t k = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
      const double s = (t - times[k]) / (times[k + 1] - times[k]);
      return (offsets[k].cast<double>() + s * (offsets[k + 1] - offsets[k]).cast<double>()).cast<float>();
    }
    case Kind::Sine: {
      const double tau = std::max(t, start) - start;
      return float(amplitude * std::sin(2.0 * std::numbers::pi * frequency * tau + phase)) * axis;
    }
  }
  return Vec3f::Zero();
}

Vec3f Motion::velocity(double t) const {
  switch (kind) {
    case Kind::None:
      break;
    case Kind::Keyframes: {
      if (times.size() < 2 || t < times.front() || t >= times.back()) break;
      const size_t k = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
      return ((offsets[k + 1] - offsets[k]).cast<double>() / (times[k + 1] - times[k])).cast<float>();
    }
    case Kind::Sine: {
      if (t < start) break;
      const double w = 2.0 * std::numbers::pi * frequency;
      return float(amplitude * w * std::cos(w * (t - start) + phase)) * axis;
    }
  }
  return Vec3f::Zero();
}

void Motion::validate(const char* where) const {
  switch (kind) {
    case Kind::None:
      break;
    case Kind::Keyframes:
      if (times.empty() || times.size() != offsets.size())
        fail(where, ": keyframe motion needs as many times as offsets, at least one (found ", times.size(), " and ",
             offsets.size(), ")");
      for (size_t k = 0; k < times.size(); ++k) {
        if (!std::isfinite(times[k]) || !finite(offsets[k])) fail(where, ": keyframe ", k, " is not finite");
        if (k > 0 && !(times[k] > times[k - 1]))
          fail(where, ": keyframe times must strictly increase (", times[k - 1], " then ", times[k], ")");
      }
      break;
    case Kind::Sine:
      if (!finite(axis) || std::abs(axis.norm() - 1.0f) > 1e-4f)
        fail(where, ": sine motion axis must be a unit vector, found length ", axis.norm());
      if (!(amplitude >= 0.0f) || !(frequency >= 0.0f) || !std::isfinite(amplitude) || !std::isfinite(frequency) ||
          !std::isfinite(phase) || !std::isfinite(start))
        fail(where, ": sine motion needs finite amplitude >= 0, frequency >= 0, phase and start");
      break;
  }
}

Solid Solid::translated(const Vec3f& offset) const {
  Solid s = *this;
  s.min += offset;
  s.max += offset;
  s.center += offset;
  return s;
}

Vec3f Solid::centre() const { return kind == Kind::Sphere ? center : Vec3f(0.5f * (min + max)); }

bool Solid::rotated() const {
  return orientation.w() != 1.0f || orientation.x() != 0.0f || orientation.y() != 0.0f || orientation.z() != 0.0f;
}

float Solid::volume() const {
  if (kind == Kind::Sphere) return 4.0f / 3.0f * std::numbers::pi_v<float> * radius * radius * radius;
  const Vec3f e = max - min;
  return e.x() * e.y() * e.z();
}

Vec3f Solid::velocity_at(const Vec3f& p) const {
  if (angular_velocity == Vec3f::Zero()) return velocity;
  return velocity + angular_velocity.cross(p - centre());
}

SolidSet::SolidSet(std::vector<Solid> solids) : solids_(std::move(solids)) { bound(); }

void SolidSet::bound() {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  bounds_.resize(solids_.size());
  for (size_t i = 0; i < solids_.size(); ++i) {
    const Solid& s = solids_[i];
    Aabb& b = bounds_[i];
    if (s.kind == Solid::Kind::Tank) {
      b.min = Vec3f::Constant(-kInf), b.max = Vec3f::Constant(kInf);
      continue;
    }
    Vec3f centre = s.centre(), extent = Vec3f::Constant(s.radius);
    if (s.kind == Solid::Kind::Box) {
      const Vec3f half = 0.5f * (s.max - s.min);
      extent = s.rotated() ? Vec3f(s.orientation.toRotationMatrix().cwiseAbs() * half) : half;
    }
    // Margins: the exact tests round by a few ulps of the coordinates (2e-6 of them is 16 ulps), and a
    // quaternion up to 1e-4 off unit length (what validate() allows) turns a point up to 2e-4 of its
    // distance from the centre off (1e-3 of the half diagonal).
    const float pad = 1e-3f * extent.norm() + 2e-6f * (centre.cwiseAbs().maxCoeff() + extent.maxCoeff());
    b.min = centre - extent - Vec3f::Constant(pad), b.max = centre + extent + Vec3f::Constant(pad);
  }
}

bool SolidSet::any_moving() const {
  return std::any_of(solids_.begin(), solids_.end(),
                     [](const Solid& s) { return s.motion.moving() || s.dynamics.enabled; });
}

bool SolidSet::any_dynamic() const {
  return std::any_of(solids_.begin(), solids_.end(), [](const Solid& s) { return s.dynamics.enabled; });
}

std::optional<GroundPlane> SolidSet::ground_below_tanks() const {
  std::optional<GroundPlane> ground;
  for (const Solid& s : solids_) {
    if (s.kind != Solid::Kind::Tank) continue;
    if (ground && ground->up_axis != s.up_axis) return std::nullopt;
    const float floor = s.min[s.up_axis];
    if (!ground || floor < ground->level) ground = GroundPlane{s.up_axis, floor};
  }
  return ground;
}

void SolidSet::validate() const {
  for (size_t i = 0; i < solids_.size(); ++i) {
    const Solid& s = solids_[i];
    const std::string where = str("solid ", i);
    s.motion.validate(where.c_str());
    const Quatf& q = s.orientation;
    if (!std::isfinite(q.w()) || !std::isfinite(q.x()) || !std::isfinite(q.y()) || !std::isfinite(q.z()) ||
        std::abs(q.norm() - 1.0f) > 1e-4f)
      fail(where, ": orientation must be a unit quaternion, found norm ", q.norm());
    if (s.kind == Solid::Kind::Tank && s.rotated()) fail(where, ": a tank cannot be rotated");
    if (!s.dynamics.enabled) continue;
    const Dynamics& d = s.dynamics;
    if (s.kind == Solid::Kind::Tank) fail(where, ": a tank cannot be dynamic (only boxes and spheres)");
    if (s.motion.moving()) fail(where, ": a dynamic solid cannot also have a motion");
    if (!(d.mass > 0.0f) && !(d.density > 0.0f))
      fail(where, ": a dynamic solid needs a density > 0 (kg/m^3) or a mass > 0 (kg); found density ", d.density,
           ", mass ", d.mass);
    if (!std::isfinite(d.mass) || !std::isfinite(d.density) || d.mass < 0.0f || d.density < 0.0f)
      fail(where, ": dynamic density and mass must be finite and >= 0");
    if (!(d.friction >= 0.0f) || !std::isfinite(d.friction))
      fail(where, ": dynamic friction must be finite and >= 0, found ", d.friction);
  }
}

SolidSet SolidSet::posed(const std::vector<BodyPose>& poses) const {
  SolidSet out = *this;
  for (const BodyPose& pose : poses) {
    if (pose.solid >= out.solids_.size() || !out.solids_[pose.solid].dynamics.enabled)
      fail("solids: body pose for solid ", pose.solid, ", which is not a dynamic solid");
    Solid& s = out.solids_[pose.solid];
    s = s.translated(pose.position - s.centre());
    s.orientation = pose.orientation;
    s.velocity = pose.velocity;
    s.angular_velocity = pose.angular_velocity;
  }
  out.bound();
  return out;
}

SolidSet SolidSet::at_time(double t) const {
  std::vector<Solid> out;
  out.reserve(solids_.size());
  for (const Solid& s : solids_) {
    if (!s.motion.moving()) {
      out.push_back(s);
      continue;
    }
    Solid moved = s.translated(s.motion.offset(t));
    moved.velocity = s.motion.velocity(t);
    moved.motion = Motion{};
    out.push_back(std::move(moved));
  }
  return SolidSet(std::move(out));
}

bool SolidSet::inside(const Vec3f& p) const {
  for (size_t i = 0; i < solids_.size(); ++i)
    if (!far_from(i, p, 0.0f) && contains(solids_[i], p)) return true;
  return false;
}

bool SolidSet::obstacle_within(const Vec3f& p, float reach) const {
  for (size_t i = 0; i < solids_.size(); ++i) {
    const Solid& s = solids_[i];
    if (s.kind == Solid::Kind::Tank || far_from(i, p, reach)) continue;
    if (s.kind == Solid::Kind::Sphere) {
      if ((p - s.center).norm() < s.radius + reach) return true;
      continue;
    }
    Vec3f normal;
    if (oriented_box_distance(s, p, normal) < reach) return true;
  }
  return false;
}

bool SolidSet::inside_other_than(const Vec3f& p, const Solid& skip) const {
  for (size_t i = 0; i < solids_.size(); ++i)
    if (&solids_[i] != &skip && !far_from(i, p, 0.0f) && contains(solids_[i], p)) return true;
  return false;
}

bool SolidSet::stop_at_tank_walls(const Vec3f& from, Vec3f& p, Vec3f& v, float skin) const {
  // The step is followed wall by wall: the earliest crossing of any wall's inner face along it stops
  // it there, the rest of the step slides along that wall (its coordinate held), and the slide is
  // followed again. Testing each wall once against the whole step misses the second wall of an edge
  // or a corner: the crossing of the x = 1 plane by a step that leaves through the floor first lies
  // below the floor, and once the floor has stopped the step nothing sees the x = 1 wall again.
  // Each stop fixes one coordinate, so a tank stops a step at most three times.
  bool moved = false;
  Vec3f start = from;
  const size_t tanks = size_t(std::count_if(solids_.begin(), solids_.end(),
                                            [](const Solid& s) { return s.kind == Solid::Kind::Tank; }));
  for (size_t stop = 0; stop < 3 * tanks; ++stop) {
    const Solid* hit = nullptr;
    int hit_axis = 0;
    bool hit_low = false;
    float hit_t = std::numeric_limits<float>::infinity();
    const Vec3f step = p - start;
    for (const Solid& s : solids_) {
      if (s.kind != Solid::Kind::Tank) continue;
      for (int a = 0; a < 3; ++a)
        for (bool low : {true, false}) {
          if (!low && s.open_top && a == s.up_axis) continue;
          const float plane = low ? s.min[a] : s.max[a];
          // From the inside of this wall's plane to beyond it.
          const bool crosses = low ? start[a] >= plane && p[a] < plane : start[a] <= plane && p[a] > plane;
          if (!crosses) continue;
          const float t = (plane - start[a]) / step[a];
          if (!(t < hit_t)) continue;
          const Vec3f at = start + t * step;
          // The crossing must lie on the wall's inner face: side walls end at the rim, so a step that
          // crosses their plane above it goes over. The tolerance covers the rounding of `at`.
          const float tolerance = 4.0f * ulp_of(std::max(at.cwiseAbs().maxCoeff(), step.cwiseAbs().maxCoeff()));
          bool on_wall = true;
          for (int b = 0; b < 3; ++b)
            on_wall &= b == a || (at[b] >= s.min[b] - tolerance && at[b] <= s.max[b] + tolerance);
          if (!on_wall) continue;
          hit = &s, hit_axis = a, hit_low = low, hit_t = t;
        }
    }
    if (!hit) break;
    const int a = hit_axis;
    const float plane = hit_low ? hit->min[a] : hit->max[a];
    Vec3f normal = Vec3f::Zero();
    normal[a] = hit_low ? 1.0f : -1.0f;
    start += hit_t * step;
    p[a] = start[a] = plane + normal[a] * representable_skin(start, skin);
    const float vn = (v - hit->velocity_at(p)).dot(normal);
    if (vn < 0.0f) v -= vn * normal;
    moved = true;
  }
  return moved;
}

bool SolidSet::push_out(Vec3f& p, Vec3f& v, float skin) const {
  bool moved = false;
  const Solid* solid = nullptr;
  auto push = [&](const Vec3f& normal, float depth) {  // depth > 0: how far p is inside along -normal
    const float step = representable_skin(p, skin);
    p += (depth + step) * normal;
    // A box or sphere far from the origin: its rounded centre can leave p an ulp inside still. Tank
    // walls are axis planes, which the skin clears exactly.
    if (solid->kind != Solid::Kind::Tank)
      for (float extra = step; contains(*solid, p) && extra < 1e3f * step; extra *= 2.0f) p += extra * normal;
    const float vn = (v - solid->velocity_at(p)).dot(normal);  // relative to a moving wall
    if (vn < 0.0f) v -= vn * normal;
    moved = true;
  };
  // Solids may touch (a box on a tank floor), so leaving one can land in another: a box is left by
  // the shallowest face that opens into free space, and a few passes settle what is left.
  constexpr int kPasses = 3;
  for (int pass = 0; pass < kPasses; ++pass) {
    const bool moved_before = moved;
    moved = false;
    for (size_t i = 0; i < solids_.size(); ++i) {
      if (far_from(i, p, 0.0f)) continue;  // not inside it
      const Solid& s = solids_[i];
      solid = &s;
      switch (s.kind) {
        case Solid::Kind::Tank: {
          const Vec3f start = p;  // the walls are judged at the point as it arrived
          for (int a = 0; a < 3; ++a) {
            if (above_open_walls(s, start, a)) continue;
            // Out by the nearer face of the wall: back inside, or (past half its thickness) outside.
            for (bool low : {true, false}) {
              if (!low && s.open_top && a == s.up_axis) continue;
              if (!in_wall_slab(s, start, a, low)) continue;
              const float depth = low ? s.min[a] - p[a] : p[a] - s.max[a];
              Vec3f n = Vec3f::Zero();
              if (depth < 0.5f * s.wall_thickness) {
                n[a] = low ? 1.0f : -1.0f;
                push(n, depth);
              } else {
                n[a] = low ? -1.0f : 1.0f;
                push(n, s.wall_thickness - depth);
              }
            }
          }
          break;
        }
        case Solid::Kind::Box: {
          Vec3f normal;
          float depth;
          if (box_exit(s, p, skin, normal, depth)) push(normal, depth);
          break;
        }
        case Solid::Kind::Sphere: {
          const Vec3f r = p - s.center;
          const float len = r.norm();
          if (len < s.radius) push(len > 0.0f ? Vec3f(r / len) : Vec3f::UnitY(), s.radius - len);
          break;
        }
      }
    }
    const bool moved_now = moved;
    moved = moved_before || moved_now;
    if (!moved_now) break;
  }
  return moved;
}

bool SolidSet::box_exit(const Solid& s, const Vec3f& p, float skin, Vec3f& normal, float& depth) const {
  const Vec3f c = s.centre(), half = 0.5f * (s.max - s.min);
  const Vec3f local = s.rotated() ? Vec3f(s.orientation.conjugate() * (p - c)) : Vec3f(p - c);
  if (!((local.cwiseAbs() - half).array() < 0.0f).all()) return false;
  // The six faces, shallowest first; ties keep the axis order, so the choice is deterministic.
  struct Face {
    float depth;
    int axis;
    float sign;
  };
  std::array<Face, 6> faces;
  for (int a = 0; a < 3; ++a) {
    faces[size_t(2 * a)] = {half[a] - local[a], a, 1.0f};
    faces[size_t(2 * a + 1)] = {half[a] + local[a], a, -1.0f};
  }
  std::stable_sort(faces.begin(), faces.end(), [](const Face& x, const Face& y) { return x.depth < y.depth; });
  for (size_t k = 0; k < faces.size(); ++k) {
    Vec3f n = Vec3f::Zero();
    n[faces[k].axis] = faces[k].sign;
    if (s.rotated()) n = s.orientation * n;
    const Vec3f exit = p + (faces[k].depth + representable_skin(p, skin)) * n;
    // The last face is taken anyway: a box buried in other solids still lets go of the point.
    if (k + 1 == faces.size() || !inside_other_than(exit, s)) {
      normal = n;
      depth = faces[k].depth;
      return true;
    }
  }
  return false;
}

}  // namespace spume
