// The wall pressure extrapolated from the fluid ([ARH12], sim/fluid/boundary_pressure.h), checked against
// sums done here by brute force over every fluid particle: the Shepard weights, the hydrostatic rise
// g . sum_f w_bf (x_b - x_f) (positive for a wall below the water, negative above it), and a wall total
// that never goes below zero.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/fluid/boundary.h"
#include "sim/fluid/boundary_pressure.h"
#include "sim/fluid/neighbours.h"
#include "sim/grid/neighbour_grid.h"
#include "tests/support/test_fluids.h"
#include "tests/support/solid_shapes.h"

namespace spume::fluid {
namespace {

constexpr float kRadius = 0.01f, kSupport = 4.0f * kRadius;
const Vec3f kGravity(0.0f, -9.81f, 0.0f);

struct PoolUnderLid {
  Boundary boundary;
  Particles particles;
  NeighbourGrid grid;
  Neighbourhoods nb;
  CubicSpline kernel{kSupport};
  WallPressure walls;
};

// A 3 x 3 x 3 block of fluid on its lattice resting on a tank floor, with a box lid 1.5 r above its
// surface: some wall particles lie below the fluid, some above it.
void build(PoolUnderLid& s) {
  const Solid tank = testing::tank_solid(Vec3f(0, 0, 0), Vec3f(0.2f, 0.2f, 0.2f));
  const Solid lid = testing::box_solid(Vec3f(0.04f, 0.075f, 0.04f), Vec3f(0.16f, 0.115f, 0.16f));
  s.boundary = sample_boundary(SolidSet({tank, lid}), 2.0f * kRadius, kSupport);
  place_boundary(s.boundary, std::vector<SolidPlacement>(2), true);
  const std::vector<Vec3f> x = testing::lattice(Vec3f(0.08f, 0.01f, 0.08f), Vec3f(0.12f, 0.05f, 0.12f), 2.0f * kRadius);
  ASSERT_EQ(x.size(), 27u);
  s.particles.resize(x.size());
  s.particles.x = x;
  for (size_t i = 0; i < x.size(); ++i) s.particles.v[i] = Vec3f::Zero(), s.particles.id[i] = uint32_t(i);
  s.grid.build(s.particles.x, kSupport);
  s.particles.reorder(s.grid.sorted_to_original());
  build_neighbourhoods(s.grid, s.boundary, s.kernel, 8.0f * kRadius * kRadius * kRadius, s.particles, s.nb);
  s.walls.build(s.nb, s.boundary, s.kernel, s.particles, kGravity);
}

TEST(FluidWallPressure, WeightsAndRiseMatchABruteForceShepardSum) {
  PoolUnderLid s;
  build(s);
  std::span<const Vec3f> bx = s.boundary.grid.sorted_points();
  ASSERT_GT(s.walls.sample.size(), 0u);
  int below = 0, above = 0;
  for (size_t k = 0; k < s.walls.sample.size(); ++k) {
    const Vec3f xb = bx[s.walls.sample[k]];
    double w_sum = 0.0, rise = 0.0;
    int within = 0;
    for (const Vec3f& xf : s.particles.x) {
      const float r = (xf - xb).norm();
      if (r > kSupport) continue;
      const double w = s.kernel.value(r);
      w_sum += w;
      rise += w * double(kGravity.dot(xb - xf));
      ++within;
    }
    ASSERT_EQ(int(s.walls.offset[k + 1] - s.walls.offset[k]), within) << "wall particle " << k;
    double listed = 0.0;
    for (uint32_t e = s.walls.offset[k]; e < s.walls.offset[k + 1]; ++e) listed += s.walls.weight[e];
    EXPECT_NEAR(listed, 1.0, 1e-5);
    EXPECT_NEAR(s.walls.rise[k], rise / w_sum, 1e-5 + 1e-4 * std::abs(rise / w_sum));
    if (xb.y() < 0.0f) {  // in the floor, below every fluid particle: deeper, so more pressure
      EXPECT_GT(s.walls.rise[k], 0.0f);
      ++below;
    }
    if (xb.y() > 0.075f) {  // in the lid, above every fluid particle
      EXPECT_LT(s.walls.rise[k], 0.0f);
      ++above;
    }
  }
  EXPECT_GT(below, 0);
  EXPECT_GT(above, 0);
}

TEST(FluidWallPressure, ExtrapolationAddsTheRiseOnceAndNeverPulls) {
  PoolUnderLid s;
  build(s);
  const size_t n = s.particles.size();
  // A uniform fluid pressure c: each wall particle takes c plus its rise, clamped at zero.
  const float c = 0.05f;
  s.walls.extrapolate(std::vector<float>(n, c), 1.0f);
  for (size_t k = 0; k < s.walls.sample.size(); ++k) {
    const uint32_t b = s.walls.sample[k];
    const float expected = std::max(c + s.walls.rise[k], 0.0f);
    EXPECT_NEAR(s.walls.k[b], expected, 1e-6f);
    EXPECT_NEAR(s.walls.total[b], expected, 1e-6f);
  }
  // A second increment without the rise: the totals grow by c, from where the clamp left them.
  std::vector<float> before(s.walls.total);
  s.walls.extrapolate(std::vector<float>(n, c), 0.0f);
  int clamped = 0;
  for (size_t k = 0; k < s.walls.sample.size(); ++k) {
    const uint32_t b = s.walls.sample[k];
    EXPECT_NEAR(s.walls.total[b], std::max(before[b] + c, 0.0f), 1e-6f);
    EXPECT_NEAR(s.walls.k[b], s.walls.total[b] - before[b], 1e-6f);
    EXPECT_GE(s.walls.total[b], 0.0f);
    clamped += c + s.walls.rise[k] < 0.0f ? 1 : 0;
  }
  // The lid lies far enough above the water that c + rise < 0 there: the first clamp did act.
  EXPECT_GT(clamped, 0);
}

}  // namespace
}  // namespace spume::fluid
