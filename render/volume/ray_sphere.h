#pragma once
// Exact ray/sphere chords, in double: the float form |oc|^2 - tc^2 cancels badly for a camera metres
// from millimetre spheres (PLATFORM_NOTES: about 1e-4 lost), double keeps ~1e-9 relative.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "sim/core/vec.h"

namespace spume {

// One chord of an eye ray through a sphere of diffuse type `type`. Distances are along the unit
// direction, relative to the ray's reference distance (its entry into the diffuse bounds), so
// float keeps about 1e-7 m over a 1 m path.
struct Interval {
  float t0, t1;   // m
  uint32_t type;  // DiffuseType
};

// Ray o + t d with |d| = 1. oc = centre - o and oc2 = |oc|^2 are per sphere, shared by many rays.
// Returns false when the ray misses or only grazes the sphere (zero-length chord).
inline bool ray_sphere_chord(const Vec3d& oc, double oc2, const Vec3d& d, double r2, double& t0, double& t1) {
  const double tc = oc.dot(d);      // distance to the point of closest approach
  const double b2 = oc2 - tc * tc;  // squared impact parameter
  if (!(b2 < r2)) return false;
  const double h = std::sqrt(r2 - b2);
  t0 = tc - h;
  t1 = tc + h;
  return true;
}

// Float directions from Camera::ray are unit only to ~1e-7; the chord formula needs |d| = 1 exactly.
inline Vec3d unit_double(const Vec3f& d) { return d.cast<double>().normalized(); }

// Ray/box slab test; returns false when the ray misses [lo, hi] or it lies behind the origin.
inline bool ray_box(const Vec3d& o, const Vec3d& d, const Vec3d& lo, const Vec3d& hi, double& t_in, double& t_out) {
  t_in = 0.0, t_out = INFINITY;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t_in = std::max(t_in, ta);
    t_out = std::min(t_out, tb);
  }
  return t_in <= t_out;
}

}  // namespace spume
