// The colour field's lattice values against the kernel sum over every particle, in double precision,
// and its sparsity: every lattice point within h of a particle lies in a stored brick.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "render/surface/colour_field.h"

namespace spume {
namespace {

constexpr double kR = 0.01, kH = 4 * kR;

// c(x) = (2r)^3 315 / (64 pi h^3) sum_j q_j^3, q_j = 1 - |x - x_j|^2 / h^2, over the particles within h
// (poly6: the same as 315 / (64 pi h^9) (h^2 - d^2)^3), and a bound
// on the float field's error: each term is q^3 (q = 1 - d^2/h^2) from a q rounded by a few ulps of 1,
// so it is off by about 3 q^2 ulps; the sums' own rounding is relative to the value.
struct KernelSum {
  double value = 0.0, tolerance = 0.0;
};
KernelSum kernel_sum(const std::vector<Vec3f>& points, const Vec3d& x) {
  const double scale = std::pow(2 * kR, 3) * 315.0 / (64.0 * std::numbers::pi * std::pow(kH, 3));
  constexpr double kQError = 8 * std::numeric_limits<float>::epsilon();  // 8 ulps of 1 in float
  double sum = 0.0, spread = 0.0;
  for (const Vec3f& p : points) {
    const double q = 1.0 - (x - p.cast<double>()).squaredNorm() / (kH * kH);
    if (q > 0.0) sum += q * q * q, spread += 3 * q * q * kQError;
  }
  return {scale * sum, scale * spread + 1e-6 * scale * sum + 1e-12};
}

// Particles scattered over several bricks, some on lattice coordinates and some about h from a
// lattice point along an axis, where a kernel's row starts or ends.
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

  // Points left out of the field read as 0: none of them may be within h of a particle.
  size_t near = 0;
  for (const Vec3f& p : points) {
    std::array<int, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(0, int(std::ceil((p[a] - kH - field.coord(a, 0)) / cell)));
      hi[a] = int(std::floor((p[a] + kH - field.coord(a, 0)) / cell));
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) {
          const Vec3d g(field.coord(0, x), field.coord(1, y), field.coord(2, z));
          if ((g - p.cast<double>()).norm() >= kH) continue;
          ++near;
          ASSERT_NE(field.find_brick(x / kB, y / kB, z / kB), SparseBins::kMissing)
              << "lattice point " << g.transpose() << " lies within h of " << p.transpose();
        }
  }
  EXPECT_GT(near, points.size() * 100);  // about 4/3 pi (h / cell)^3 points a particle
}

TEST(ColourField, EveryLatticeValueIsTheKernelSumOverAllParticles) {
  for (uint32_t seed : {1u, 2u, 3u}) expect_kernel_sums(cloud(seed, float(kR)), float(kR));
}

TEST(ColourField, HalfRadiusCellsToo) { expect_kernel_sums(cloud(4, float(kR / 2)), float(kR / 2)); }

}  // namespace
}  // namespace spume
