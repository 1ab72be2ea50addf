#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace spume {

using Vec3f = Eigen::Vector3f;
using Vec3d = Eigen::Vector3d;

// Axis-aligned box; empty when min > max on any axis.
struct Aabb {
  Vec3f min = Vec3f::Constant(INFINITY);
  Vec3f max = Vec3f::Constant(-INFINITY);

  void extend(const Vec3f& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
  bool empty() const { return (min.array() > max.array()).any(); }
  bool contains(const Vec3f& p) const { return (p.array() >= min.array()).all() && (p.array() <= max.array()).all(); }
};

inline bool finite(const Vec3f& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

}  // namespace spume
