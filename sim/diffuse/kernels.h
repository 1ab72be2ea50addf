#pragma once
// The scalar functions of the diffuse model (MODEL.md §1, §4). Header-only: they sit in hot loops.
#include <algorithm>
#include <cmath>
#include <numbers>

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

// Cubic spline (Monaghan's M4) in q = r / h with compact support h: W(r) = 8 / (pi h^3) f(q) and
// dW/dr = 8 / (pi h^4) f'(q). Written without branches on q > 1 so the lane loops vectorise.
inline float cubic_spline_shape(float q) {
  const float t = std::max(1.0f - q, 0.0f);
  return q <= 0.5f ? 6.0f * (q * q * q - q * q) + 1.0f : 2.0f * t * t * t;
}
// f'(q), taking q^2 as well since the callers have it.
inline float cubic_spline_slope(float q, float q2) {
  const float t = std::max(1.0f - q, 0.0f);
  return q <= 0.5f ? 18.0f * q2 - 12.0f * q : -6.0f * t * t;
}

// The cubic spline normalised in 3D, for one support radius h.
struct CubicSpline {
  float h;
  float sigma;  // 8 / (pi h^3)
  explicit CubicSpline(float support) : h(support), sigma(8.0f / (std::numbers::pi_v<float> * support * support * support)) {}

  float value(float r) const { return sigma * cubic_spline_shape(r / h); }
  // dW/dr: the gradient is derivative(r) * x/r.
  float derivative(float r) const {
    const float q = r / h;
    return sigma / h * cubic_spline_slope(q, q * q);
  }
};

// Any orthonormal pair perpendicular to unit vector n (Duff et al. 2017, branch on the sign of n.z).
inline void orthonormal_basis(const Vec3f& n, Vec3f& e1, Vec3f& e2) {
  const float sign = std::copysign(1.0f, n.z());
  const float a = -1.0f / (sign + n.z());
  const float b = n.x() * n.y() * a;
  e1 = Vec3f(1.0f + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  e2 = Vec3f(b, sign + n.y() * n.y() * a, -n.y());
}

}  // namespace spume
