#pragma once
// The scalar functions of the diffuse model (MODEL.md §1, §4). Header-only: they sit in hot loops.
#include <cmath>
#include <numbers>

#include "core/vec.h"

namespace spume {

// Eq. 1: clamp I to [lo, hi] and scale to [0, 1]. Callers guarantee lo < hi (validated at the scene
// boundary, MODEL.md §8.1), so this never divides by zero.
inline float clamp_and_scale(float value, float lo, float hi) {
  return (std::min(value, hi) - std::min(value, lo)) / (hi - lo);
}

// Eq. 3: the paper's radially symmetric weight, deliberately not normalised.
inline float paper_weight(float distance, float h) { return distance <= h ? 1.0f - distance / h : 0.0f; }

// Cubic spline kernel with compact support h (Monaghan's M4 with q = r/h in [0, 1]), normalised in 3D.
struct CubicSpline {
  float h;
  float sigma;  // 8 / (pi h^3)
  explicit CubicSpline(float support) : h(support), sigma(8.0f / (std::numbers::pi_v<float> * support * support * support)) {}

  float value(float r) const {
    const float q = r / h;
    if (q > 1.0f) return 0.0f;
    if (q <= 0.5f) return sigma * (6.0f * (q * q * q - q * q) + 1.0f);
    const float t = 1.0f - q;
    return sigma * 2.0f * t * t * t;
  }
  // dW/dr: the gradient is derivative(r) * x/r.
  float derivative(float r) const {
    const float q = r / h;
    if (q > 1.0f) return 0.0f;
    if (q <= 0.5f) return sigma / h * (18.0f * q * q - 12.0f * q);
    const float t = 1.0f - q;
    return -sigma / h * 6.0f * t * t;
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

// Volume of the part of a sphere of radius h lying beyond a plane at signed distance d from its
// centre (d > 0: the centre is on the near side). Used to count a solid's missing fluid neighbours.
inline float sphere_cap_volume(float d, float h) {
  const float x = std::clamp(d, -h, h);
  return std::numbers::pi_v<float> * (h - x) * (h - x) * (2.0f * h + x) / 3.0f;
}

}  // namespace spume
