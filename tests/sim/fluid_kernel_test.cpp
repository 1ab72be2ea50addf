// The fluid solver's cubic spline: normalisation, gradient and the lattice sum that makes the
// particle mass rho0 (2r)^3 rest at rho0 (all from the closed form, not from solver output).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/core/cubic_spline.h"

namespace spume::fluid {
namespace {

TEST(FluidKernel, IntegratesToOne) {
  const float h = 0.04f;
  const CubicSpline k(h);
  // Midpoint rule on a 200^3 grid over the support's bounding cube.
  const int n = 200;
  const double dx = 2.0 * h / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int l = 0; l < n; ++l) {
        const double x = -h + (i + 0.5) * dx, y = -h + (j + 0.5) * dx, z = -h + (l + 0.5) * dx;
        sum += k.value(float(std::sqrt(x * x + y * y + z * z)));
      }
  EXPECT_NEAR(sum * dx * dx * dx, 1.0, 1e-4);
}

TEST(FluidKernel, GradientIsTheRadialDerivative) {
  const float h = 0.04f;
  const CubicSpline k(h);
  // dW/dr of Monaghan's M4 in closed form (double), and a central difference of W as a cross-check.
  const double sigma = 8.0 / (std::numbers::pi * h * h * h);
  for (double q : {0.05, 0.2, 0.45, 0.55, 0.8, 0.97}) {
    const double r = q * h;
    const double exact = q <= 0.5 ? sigma / h * (18 * q * q - 12 * q) : -6 * sigma / h * (1 - q) * (1 - q);
    EXPECT_NEAR(double(k.grad_factor(float(r))) * r, exact, 1e-5 * std::abs(exact)) << "q = " << q;
    const double e = 1e-3 * h;
    const double fd = (double(k.value(float(r + e))) - double(k.value(float(r - e)))) / (2 * e);
    EXPECT_NEAR(fd, exact, 1e-2 * std::abs(exact)) << "q = " << q;
  }
  EXPECT_EQ(k.value(1.01f * h), 0.0f);
  EXPECT_EQ(k.grad_factor(1.01f * h), 0.0f);
  EXPECT_TRUE(std::isfinite(k.grad_factor(0.0f)));
}

TEST(FluidKernel, LatticeOfSpacing2rSumsToRestDensity) {
  // h = 4r, lattice spacing d = 2r: sum_j W(x_j) d^3 = 1, so m = rho0 d^3 gives rho0 at rest.
  const float r = 0.01f, d = 2 * r;
  const CubicSpline k(4 * r);
  double sum = 0.0;
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j)
      for (int l = -3; l <= 3; ++l) sum += k.value(d * std::sqrt(float(i * i + j * j + l * l)));
  EXPECT_NEAR(sum * d * d * d, 1.0, 1e-3);
}

}  // namespace
}  // namespace spume::fluid
