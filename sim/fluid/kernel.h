#pragma once
// The SPH kernel of the fluid solver: the cubic spline (M4) with compact support h, normalised in 3D,
// W(q) = s * (6 (q^3 - q^2) + 1) for q <= 1/2 and s * 2 (1 - q)^3 for q <= 1, q = |x| / h,
// s = 8 / (pi h^3) [Monaghan 1992, with support h instead of 2h]. With h = 4r on a lattice of
// spacing 2r its sum over the lattice is 1 / (2r)^3 to 1e-4, so m = rho0 (2r)^3 rests at rho0.
// Header-only: it sits in the innermost loops.
#include <numbers>

namespace spume::fluid {

struct Kernel {
  float h = 1.0f, h2 = 1.0f, inv_h = 1.0f;
  float sigma = 0.0f;       // 8 / (pi h^3)
  float grad_sigma = 0.0f;  // 48 / (pi h^5): the common factor of dW/dr / r

  explicit Kernel(float support)
      : h(support), h2(support * support), inv_h(1.0f / support),
        sigma(8.0f / (std::numbers::pi_v<float> * support * support * support)),
        grad_sigma(6.0f * sigma / (support * support)) {}

  float W0() const { return sigma; }

  // W at distance r (r >= 0).
  float W(float r) const {
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
};

}  // namespace spume::fluid
