#include "solids.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.h"
#include "diffuse/kernels.h"

namespace spume {
namespace {

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

bool SolidSet::any_moving() const {
  return std::any_of(solids_.begin(), solids_.end(), [](const Solid& s) { return s.motion.moving(); });
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
  Vec3f q = p, v = Vec3f::Zero();
  return push_out(q, v, 0.0f);
}

float SolidSet::solid_volume_within(const Vec3f& p, float h) const {
  float volume = 0.0f;
  for (const Solid& s : solids_) {
    switch (s.kind) {
      case Solid::Kind::Tank:
        for (int a = 0; a < 3; ++a) {
          if (a != s.up_axis && p[s.up_axis] > s.max[s.up_axis]) continue;  // above the side walls
          volume += sphere_cap_volume(p[a] - s.min[a], h);
          if (!(s.open_top && a == s.up_axis)) volume += sphere_cap_volume(s.max[a] - p[a], h);
        }
        break;
      case Solid::Kind::Box: {
        Vec3f n;
        volume += sphere_cap_volume(box_distance(p, s.min, s.max, n), h);
        break;
      }
      case Solid::Kind::Sphere:
        volume += sphere_cap_volume((p - s.center).norm() - s.radius, h);
        break;
    }
  }
  return std::min(volume, 4.0f / 3.0f * std::numbers::pi_v<float> * h * h * h);
}

bool SolidSet::push_out(Vec3f& p, Vec3f& v, float skin) const {
  bool moved = false;
  const Vec3f* wall_velocity = nullptr;
  auto push = [&](const Vec3f& normal, float depth) {  // depth > 0: how far p is inside along -normal
    p += (depth + skin) * normal;
    const float vn = (v - *wall_velocity).dot(normal);  // relative to a moving wall
    if (vn < 0.0f) v -= vn * normal;
    moved = true;
  };
  for (const Solid& s : solids_) {
    wall_velocity = &s.velocity;
    switch (s.kind) {
      case Solid::Kind::Tank:
        for (int a = 0; a < 3; ++a) {
          if (a != s.up_axis && p[s.up_axis] > s.max[s.up_axis]) continue;  // passing over a side wall
          Vec3f n = Vec3f::Zero();
          if (p[a] < s.min[a]) {
            n[a] = 1.0f;
            push(n, s.min[a] - p[a]);
          }
          if (!(s.open_top && a == s.up_axis) && p[a] > s.max[a]) {
            n[a] = -1.0f;
            push(n, p[a] - s.max[a]);
          }
        }
        break;
      case Solid::Kind::Box: {
        Vec3f n;
        const float d = box_distance(p, s.min, s.max, n);
        if (d < 0.0f) push(n, -d);
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
  return moved;
}

}  // namespace spume
