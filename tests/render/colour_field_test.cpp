// The colour field's lattice values against the kernel sum over every particle, in double precision.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "render/surface/colour_field.h"

namespace spume {
namespace {

constexpr double kR = 0.01, kH = 4 * kR;

// c(x) = (2r)^3 315 / (64 pi h^9) sum_j (h^2 - |x - x_j|^2)^3 over the particles within h, and a bound
// on the float field's error: each term is q^3 (q = 1 - d^2/h^2) from a q rounded by a few ulps of 1,
// so it is off by about 3 q^2 ulps; the sums' own rounding is relative to the value.
struct KernelSum {
  double value = 0.0, tolerance = 0.0;
};
KernelSum kernel_sum(const std::vector<Vec3f>& points, const Vec3d& x) {
  const double scale = std::pow(2 * kR, 3) * 315.0 / (64.0 * std::numbers::pi * std::pow(kH, 3));
  constexpr double kQError = 8 * 1.2e-7;  // 8 ulps of 1 in float
  double sum = 0.0, spread = 0.0;
  for (const Vec3f& p : points) {
    const double q = 1.0 - (x - p.cast<double>()).squaredNorm() / (kH * kH);
    if (q > 0.0) sum += q * q * q, spread += 3 * q * q * kQError;
  }
  return {scale * sum, scale * spread + 1e-6 * scale * sum + 1e-12};
}

// Particles scattered over several bricks, some on lattice coordinates and some at exactly h from
// a lattice point along an axis, where a kernel's row starts or ends.
std::vector<Vec3f> cloud(uint32_t seed, float cell) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 0.25f);
  std::vector<Vec3f> p;
  for (int i = 0; i < 600; ++i) p.emplace_back(u(rng), u(rng), u(rng));
  for (int i = 0; i < 100; ++i) {
    Vec3f on = (p[size_t(i)] / cell).array().round() * cell;
    p.push_back(on);
    p.push_back(on + Vec3f(float(kH), 0.0f, 0.0f));
  }
  return p;
}

void expect_kernel_sums(const std::vector<Vec3f>& points, float cell) {
  const ColourField field(points, float(kR), float(kH), cell);
  ASSERT_GT(field.brick_count(), 8u);
  constexpr int kB = ColourField::kB;
  size_t checked = 0, inside = 0;
  for (size_t b = 0; b < field.brick_count(); ++b) {
    const auto c = field.brick_coords(b);
    const auto values = field.values(b);
    for (int k = 0; k < kB; ++k)
      for (int j = 0; j < kB; ++j)
        for (int i = 0; i < kB; ++i) {
          const Vec3d x(field.coord(0, c[0] * kB + i), field.coord(1, c[1] * kB + j), field.coord(2, c[2] * kB + k));
          const KernelSum expected = kernel_sum(points, x);
          const double got = values[size_t((k * kB + j) * kB + i)];
          ASSERT_NEAR(got, expected.value, expected.tolerance)
              << "brick " << b << " point " << i << "," << j << "," << k << " at " << x.transpose();
          ++checked;
          inside += expected.value > 0.0;
        }
  }
  EXPECT_GT(inside, checked / 4);  // most points lie within some particle's reach
}

TEST(ColourField, EveryLatticeValueIsTheKernelSumOverAllParticles) {
  for (uint32_t seed : {1u, 2u, 3u}) expect_kernel_sums(cloud(seed, float(kR)), float(kR));
}

TEST(ColourField, HalfRadiusCellsToo) { expect_kernel_sums(cloud(4, float(kR / 2)), float(kR / 2)); }

}  // namespace
}  // namespace spume
