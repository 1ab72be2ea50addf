#pragma once
// The scalar functions of the diffuse model (MODEL.md §1, §4), beside the SPH kernel it shares with
// the fluid solver (core/cubic_spline.h). Header-only: they sit in hot loops.
#include <algorithm>
#include <cmath>

#include "sim/core/cubic_spline.h"
#include "sim/core/vec.h"

namespace spume {

// Eq. 1: clamp I to [lo, hi] and scale to [0, 1]. Callers guarantee lo < hi (validated at the scene
// boundary, MODEL.md §8.1), so this never divides by zero.
inline float clamp_and_scale(float value, float lo, float hi) {
  return (std::min(value, hi) - std::min(value, lo)) / (hi - lo);
}

// Eq. 3: the paper's radially symmetric weight, deliberately not normalised; q = distance / h.
inline float paper_weight_at(float q) { return std::max(1.0f - q, 0.0f); }
inline float paper_weight(float distance, float h) { return paper_weight_at(distance / h); }

// Any orthonormal pair perpendicular to unit vector n (Duff et al. 2017, branch on the sign of n.z).
inline void orthonormal_basis(const Vec3f& n, Vec3f& e1, Vec3f& e2) {
  const float sign = std::copysign(1.0f, n.z());
  const float a = -1.0f / (sign + n.z());
  const float b = n.x() * n.y() * a;
  e1 = Vec3f(1.0f + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  e2 = Vec3f(b, sign + n.y() * n.y() * a, -n.y());
}

}  // namespace spume
