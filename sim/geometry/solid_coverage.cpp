#include "sim/geometry/solid_coverage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "sim/core/cubic_spline.h"

namespace spume {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kSigma = CubicSpline::kSigmaNumerator / kPi;  // cubic spline: W(r) = sigma / h^3 f(r / h)

// Spherical Fibonacci points: nearly equal areas, so every direction carries the weight 4 pi / N.
const std::array<Vec3f, kCoverageDirections>& directions() {
  static const std::array<Vec3f, kCoverageDirections> table = [] {
    std::array<Vec3f, kCoverageDirections> u;
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < kCoverageDirections; ++k) {
      const double z = 1.0 - (2.0 * k + 1.0) / kCoverageDirections;
      const double rho = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = golden * k;
      u[size_t(k)] = Vec3d(rho * std::cos(phi), rho * std::sin(phi), z).cast<float>();
    }
    return u;
  }();
  return table;
}

// Antiderivatives in q = r / h of the cubic spline's radial integrals, piecewise at q = 1/2:
//   gradient_radial(q) = ∫_0^q f'(s) s^2 ds     (∫ W'(r) r^2 dr = sigma / h * this)
//   plane_radial(q)    = ∫_0^q f(s) s ds        (∫ W(r) r dr   = sigma / h * this)
// with f(q) = 6 (q^3 - q^2) + 1 for q <= 1/2 and 2 (1 - q)^3 above.
double gradient_radial(double q) {
  q = std::clamp(q, 0.0, 1.0);
  if (q <= 0.5) return 18.0 * std::pow(q, 5) / 5.0 - 3.0 * std::pow(q, 4);
  auto outer = [](double s) { return -2.0 * s * s * s + 3.0 * std::pow(s, 4) - 1.2 * std::pow(s, 5); };
  return gradient_radial(0.5) + outer(q) - outer(0.5);
}

double plane_radial(double q) {
  q = std::clamp(q, 0.0, 1.0);
  if (q <= 0.5) return 1.2 * std::pow(q, 5) - 1.5 * std::pow(q, 4) + 0.5 * q * q;
  auto outer = [](double s) { return -0.5 * std::pow(1.0 - s, 4) + 0.4 * std::pow(1.0 - s, 5); };
  return plane_radial(0.5) + outer(q) - outer(0.5);
}

struct Interval {
  float a, b;
};

// Parameters t where o + t d lies within [lo, hi] along one axis: a possibly infinite interval, or
// empty (a > b).
Interval slab(float o, float d, float lo, float hi) {
  if (d == 0.0f) return o >= lo && o <= hi ? Interval{-kInf, kInf} : Interval{kInf, -kInf};
  const float t0 = (lo - o) / d, t1 = (hi - o) / d;
  return {std::min(t0, t1), std::max(t0, t1)};
}

Interval intersect(Interval x, Interval y) { return {std::max(x.a, y.a), std::min(x.b, y.b)}; }

// Collects the parts of the ray segment t in [0, h] that lie inside solids.
class SegmentSet {
 public:
  explicit SegmentSet(float h) : h_(h) {}
  void add(Interval s) {
    s.a = std::max(s.a, 0.0f), s.b = std::min(s.b, h_);
    if (s.a < s.b && count_ < parts_.size()) parts_[count_++] = s;
  }
  // [0, h] minus the free intervals (at most two of them, possibly overlapping).
  void add_complement(Interval f1, Interval f2) {
    if (f1.a > f1.b) f1 = f2;
    if (f2.a > f2.b) f2 = f1;
    if (f1.a > f2.a) std::swap(f1, f2);
    if (f1.a > f1.b) return add({0.0f, h_});  // nothing free
    if (f2.a <= f1.b) f1.b = std::max(f1.b, f2.b), f2 = f1;  // they overlap: one free interval
    add({-kInf, f1.a});
    if (f2.a > f1.b) add({f1.b, f2.a});
    add({std::max(f1.b, f2.b), kInf});
  }
  // Sorts and merges, then calls fn(a, b) for each disjoint part.
  template <typename Fn>
  void for_each_union(Fn&& fn) {
    std::sort(parts_.begin(), parts_.begin() + count_, [](const Interval& x, const Interval& y) { return x.a < y.a; });
    size_t k = 0;
    while (k < count_) {
      Interval u = parts_[k++];
      while (k < count_ && parts_[k].a <= u.b) u.b = std::max(u.b, parts_[k++].b);
      fn(u.a, u.b);
    }
  }

 private:
  float h_;
  // More solids than this within h of one point: the rest is ignored. Left uninitialised: only the
  // first count_ are read, and the integral builds one set for each of its 256 directions.
  std::array<Interval, 64> parts_;
  size_t count_ = 0;
};

// A solid near the point integrated around, with what does not depend on the direction: for a box,
// the point in the box's own frame and the rotation into it.
struct NearSolid {
  const Solid* solid = nullptr;
  bool rotated = false;
  Quatf to_box = Quatf::Identity();
  Vec3f origin = Vec3f::Zero();  // p in the box's frame (p itself when not rotated)

  NearSolid() = default;
  NearSolid(const Solid& s, const Vec3f& p) : solid(&s), rotated(s.kind == Solid::Kind::Box && s.rotated()), origin(p) {
    if (!rotated) return;
    const Vec3f c = s.centre();
    to_box = s.orientation.conjugate();
    origin = c + to_box * (p - c);
  }
};

void add_solid_segments(const NearSolid& near, const Vec3f& p, const Vec3f& u, SegmentSet& segments) {
  const Solid& s = *near.solid;
  switch (s.kind) {
    case Solid::Kind::Box: {
      const Vec3f& o = near.origin;
      const Vec3f d = near.rotated ? Vec3f(near.to_box * u) : u;
      Interval in{-kInf, kInf};
      for (int a = 0; a < 3; ++a) in = intersect(in, slab(o[a], d[a], s.min[a], s.max[a]));
      segments.add(in);
      break;
    }
    case Solid::Kind::Sphere: {
      const Vec3f oc = p - s.center;
      const float b = u.dot(oc), c = oc.squaredNorm() - s.radius * s.radius, disc = b * b - c;
      if (disc > 0.0f) segments.add({-b - std::sqrt(disc), -b + std::sqrt(disc)});
      break;
    }
    case Solid::Kind::Tank: {
      // Free space: inside the box; with an open top also anything above the rim (the side walls
      // end there). Everything else is wall.
      const int up = s.up_axis;
      Interval sides{-kInf, kInf};
      for (int a = 0; a < 3; ++a)
        if (a != up) sides = intersect(sides, slab(p[a], u[a], s.min[a], s.max[a]));
      if (!s.open_top) {
        segments.add_complement(intersect(sides, slab(p[up], u[up], s.min[up], s.max[up])), {kInf, -kInf});
        break;
      }
      const Interval above_floor = slab(p[up], u[up], s.min[up], kInf);
      const Interval above_rim = slab(p[up], u[up], s.max[up], kInf);
      segments.add_complement(intersect(above_floor, sides), intersect(above_floor, above_rim));
      break;
    }
  }
}

// The solids within reach of the ball (a scene of many boxes has only a few near any point).
struct NearSolids {
  std::array<NearSolid, 32> solid;
  size_t count = 0;
};

SolidCoverage integrate_directions(const NearSolids& near, const Vec3f& p, float h, bool with_gradient) {
  const float weight = 4.0f * kPi / kCoverageDirections;
  double volume = 0.0;
  Vec3d gradient = Vec3d::Zero();
  for (const Vec3f& u : directions()) {
    SegmentSet segments(h);
    for (size_t k = 0; k < near.count; ++k) add_solid_segments(near.solid[k], p, u, segments);
    double v = 0.0, g = 0.0;
    segments.for_each_union([&](float a, float b) {
      v += (double(b) * b * b - double(a) * a * a) / 3.0;
      if (with_gradient) g += gradient_radial(b / h) - gradient_radial(a / h);
    });
    volume += v;
    // ∇_x W(x - y) at y = x + r u is W'(r) (-u); the radial integral of W' r^2 is sigma / h * g.
    if (with_gradient) gradient -= g * u.cast<double>();
  }
  SolidCoverage c;
  c.fraction = float(std::clamp(weight * volume / (4.0 / 3.0 * std::numbers::pi * h * h * h), 0.0, 1.0));
  c.gradient = (double(weight) * kSigma / h * gradient).cast<float>();
  return c;
}

// A flat face near p: its unit normal pointing into the solid and p's signed distance to it
// (positive on the free side).
struct Face {
  Vec3f into_solid = Vec3f::Zero();
  float distance = 0.0f;
};

enum class Near { Nothing, OneFace, Complex };

// What of solid s the ball of radius h around p meets: nothing, a single flat face whose contact
// disc lies inside the face (then `face` is set), or anything else.
Near classify_solid(const Solid& s, const Vec3f& p, float h, Face& face) {
  switch (s.kind) {
    case Solid::Kind::Sphere:
      return (p - s.center).norm() - s.radius < h ? Near::Complex : Near::Nothing;
    case Solid::Kind::Box: {
      const Vec3f c = s.centre(), half = 0.5f * (s.max - s.min);
      const Vec3f local = s.rotated() ? Vec3f(s.orientation.conjugate() * (p - c)) : Vec3f(p - c);
      const Vec3f gap = local.cwiseAbs() - half;  // > 0: outside that slab
      if (gap.maxCoeff() >= h) return Near::Nothing;
      int axis = 0;
      gap.maxCoeff(&axis);
      // Single face: the ball stays inside the other two slabs and short of the far face.
      for (int b = 0; b < 3; ++b)
        if (b != axis && gap[b] > -h) return Near::Complex;
      if (2.0f * half[axis] + gap[axis] < h) return Near::Complex;
      Vec3f n = Vec3f::Zero();
      n[axis] = local[axis] >= 0.0f ? -1.0f : 1.0f;
      face = {s.rotated() ? Vec3f(s.orientation * n) : n, gap[axis]};
      return Near::OneFace;
    }
    case Solid::Kind::Tank: {
      const int up = s.up_axis;
      int near_faces = 0;
      for (int a = 0; a < 3; ++a) {
        const float below = p[a] - s.min[a], beyond = s.max[a] - p[a];
        const bool has_max_wall = !(s.open_top && a == up);
        if (below < h) {
          ++near_faces, face = {Vec3f::Zero(), below};
          face.into_solid[a] = -1.0f;
        }
        if (has_max_wall && beyond < h) {
          ++near_faces, face = {Vec3f::Zero(), beyond};
          face.into_solid[a] = 1.0f;
        }
      }
      if (near_faces == 0) return Near::Nothing;
      // Near a side wall and within h of an open rim, the wall ends inside the ball.
      const bool near_side_wall = near_faces > 1 || face.into_solid[up] == 0.0f;
      if (s.open_top && near_side_wall && p[up] + h > s.max[up]) return Near::Complex;
      return near_faces == 1 ? Near::OneFace : Near::Complex;
    }
  }
  return Near::Complex;
}

double cap_fraction(float distance, float h) {
  const double x = double(std::clamp(distance, -h, h)) / h;
  return (1.0 - x) * (1.0 - x) * (2.0 + x) / 4.0;  // cap volume / (4/3 pi h^3)
}

}  // namespace

CoverageBounds solid_coverage_bounds(const SolidSet& solids, const Vec3f& p, float h) {
  double hi = 0.0, lo = 0.0;
  int faces = 0;
  bool complex = false;
  Face face{};
  for (size_t i = 0; i < solids.solids().size(); ++i) {
    if (solids.far_from(i, p, h)) continue;
    const Solid& s = solids.solids()[i];
    const Near what = classify_solid(s, p, h, face);
    if (what == Near::Nothing) continue;
    if (what == Near::OneFace) {
      ++faces;
      const double cap = cap_fraction(face.distance, h);
      hi += cap, lo = std::max(lo, cap);
      continue;
    }
    complex = true;
    switch (s.kind) {
      case Solid::Kind::Sphere:  // inside the half-space beyond its tangent plane
        hi += cap_fraction((p - s.center).norm() - s.radius, h);
        break;
      case Solid::Kind::Box: {  // inside the half-space behind its farthest-out face plane
        const Vec3f local = s.rotated() ? Vec3f(s.orientation.conjugate() * (p - s.centre())) : Vec3f(p - s.centre());
        hi += cap_fraction((local.cwiseAbs() - 0.5f * (s.max - s.min)).maxCoeff(), h);
        break;
      }
      case Solid::Kind::Tank: {  // the walls lie beyond their planes; below the rim each is all wall
        const bool below_rim = !s.open_top || p[s.up_axis] + h <= s.max[s.up_axis];
        for (int a = 0; a < 3; ++a)
          for (bool low : {true, false}) {
            if (!low && s.open_top && a == s.up_axis) continue;
            const float d = low ? p[a] - s.min[a] : s.max[a] - p[a];
            if (d >= h) continue;
            const double cap = cap_fraction(d, h);
            hi += cap;
            if (below_rim || a == s.up_axis) lo = std::max(lo, cap);
          }
        break;
      }
    }
  }
  if (!complex && faces <= 1) return {float(lo), float(lo)};  // exact: nothing, or one flat face
  return {float(lo), float(std::min(hi, 1.0))};
}

SolidCoverage solid_coverage(const SolidSet& solids, const Vec3f& p, float h, bool with_gradient) {
  Face face{}, found{};
  int faces = 0;
  bool complex = false;
  NearSolids near;
  for (size_t i = 0; i < solids.solids().size(); ++i) {
    if (solids.far_from(i, p, h)) continue;
    const Solid& s = solids.solids()[i];
    const Near what = classify_solid(s, p, h, face);
    if (what == Near::Nothing) continue;
    if (near.count < near.solid.size()) near.solid[near.count++] = NearSolid(s, p);
    if (what == Near::OneFace) ++faces, found = face;
    else complex = true;
  }
  if (near.count == 0) return {};
  if (complex || faces > 1) return integrate_directions(near, p, h, with_gradient);
  // One flat face: the solid part of the ball is the cap beyond the plane.
  SolidCoverage c;
  const double x = double(std::clamp(found.distance, -h, h)) / h;
  c.fraction = float(cap_fraction(found.distance, h));
  if (with_gradient) {
    // Divergence theorem: the integral of ∇W over the cap is the normal times the integral of W over
    // the flat disc, 2 pi ∫_|d|^h W(s) s ds (the same for p on either side of the plane).
    const double disc = 2.0 * std::numbers::pi * kSigma / h * (plane_radial(1.0) - plane_radial(std::abs(x)));
    c.gradient = float(disc) * found.into_solid;
  }
  return c;
}

}  // namespace spume
