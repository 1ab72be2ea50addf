#pragma once
// The SPH kernel of spume, one for the fluid solver and the diffuse model: the cubic spline (Monaghan's
// M4) with compact support h, normalised in 3D,
//   W(r) = sigma f(q),  q = r / h,  sigma = 8 / (pi h^3),
//   f(q) = 6 (q^3 - q^2) + 1 for q <= 1/2,  2 (1 - q)^3 for q <= 1,  0 beyond
// [Monaghan 1992, with support h instead of 2h]. With h = 4r on a lattice of spacing 2r its sum over
// the lattice is 1 / (2r)^3 to 1e-4, so m = rho0 (2r)^3 rests at rho0. The fluid solver uses value()
// and grad_factor(); the diffuse model's surface normals use the slope f'(q) in their lane loops
// (cubic_spline_slope), with sigma / h^2 folded into one factor there (diffuse/potentials.cpp).
// Header-only: it sits in the innermost loops.
#include <algorithm>
#include <numbers>

namespace spume {

// f'(q), taking q^2 as well since the callers have it; 0 beyond the support. Written without branches
// on q > 1 so the lane loops vectorise.
inline float cubic_spline_slope(float q, float q2) {
  const float t = std::max(1.0f - q, 0.0f);
  return q <= 0.5f ? 18.0f * q2 - 12.0f * q : -6.0f * t * t;
}

// The kernel for one support radius h.
struct CubicSpline {
  // The 3D normalisation's numerator: sigma = 8 / (pi h^3). Callers that fold sigma into their own
  // factors (the diffuse normals, the solids' coverage) read it here.
  static constexpr float kSigmaNumerator = 8.0f;

  float h = 1.0f, h2 = 1.0f, inv_h = 1.0f;
  float sigma = 0.0f;       // 8 / (pi h^3)
  float grad_sigma = 0.0f;  // 48 / (pi h^5): the common factor of dW/dr / r

  explicit CubicSpline(float support)
      : h(support), h2(support * support), inv_h(1.0f / support),
        sigma(kSigmaNumerator / (std::numbers::pi_v<float> * support * support * support)),
        grad_sigma(6.0f * sigma / (support * support)) {}

  float value_at_zero() const { return sigma; }

  // W at distance r (r >= 0).
  float value(float r) const {
    const float q = r * inv_h;
    if (q > 1.0f) return 0.0f;
    if (q <= 0.5f) return sigma * (6.0f * (q * q * q - q * q) + 1.0f);
    const float t = 1.0f - q;
    return sigma * 2.0f * t * t * t;
  }

  // (dW/dr) / r at distance r: grad W(x) = grad_factor(|x|) * x. Finite at r = 0 (limit -12 s / h^2),
  // where x = 0 makes the gradient vanish without a division by zero.
  float grad_factor(float r) const {
    const float q = r * inv_h;
    if (q > 1.0f) return 0.0f;
    if (q <= 0.5f) return grad_sigma * (3.0f * q - 2.0f);  // (s/h)(18q^2 - 12q) / (q h)
    const float t = 1.0f - q;
    return q > 0.0f ? -grad_sigma * t * t / q : 0.0f;       // -(s/h) 6 t^2 / (q h)
  }

  // dW/dr = sigma / h f'(q), through the slope the diffuse lane loops use: grad W = derivative(r) x / r.
  float derivative(float r) const {
    const float q = r * inv_h;
    return sigma * inv_h * cubic_spline_slope(q, q * q);
  }
};

}  // namespace spume
