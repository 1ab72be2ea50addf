#pragma once
// Solids for geometry tests, built from their corners or centre.
#include "sim/geometry/solids.h"

namespace spume::testing {

inline Solid tank_solid(const Vec3f& lo, const Vec3f& hi, bool open_top = true) {
  Solid s;
  s.kind = Solid::Kind::Tank;
  s.min = lo, s.max = hi, s.open_top = open_top;
  return s;
}

inline Solid box_solid(const Vec3f& lo, const Vec3f& hi, const Quatf& orientation = Quatf::Identity()) {
  Solid s;
  s.kind = Solid::Kind::Box;
  s.min = lo, s.max = hi, s.orientation = orientation;
  return s;
}

inline Solid sphere_solid(const Vec3f& centre, float radius) {
  Solid s;
  s.kind = Solid::Kind::Sphere;
  s.center = centre, s.radius = radius;
  return s;
}

}  // namespace spume::testing
