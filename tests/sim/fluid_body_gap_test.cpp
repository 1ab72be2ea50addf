// The pressure solves' factor alpha_i of a particle in a gap between two dynamic bodies (issue 47: the
// paper's tower blew up at t = 0.667 s). Across a gap narrower than a particle the two faces' pulls
// cancel, so a particle with few fluid neighbours barely changes its own density rate by moving, and
// alpha_i = 1 / (|sum grad|^2 + sum over fluid neighbours |grad|^2) grew without bound: the solve put
// pressure on it that could not move it and went to the two light bodies as a spin, which doubled
// every few steps. A dynamic body's boundary particles move with the body, so they count in the
// second sum as fluid neighbours do; a static wall's do not.
#include <gtest/gtest.h>

#include <cmath>
#include <span>
#include <vector>

#include "sim/core/cubic_spline.h"
#include "sim/fluid/boundary.h"
#include "sim/fluid/neighbours.h"
#include "sim/fluid/particles.h"
#include "tests/support/solid_shapes.h"

namespace spume::fluid {
namespace {

constexpr float kRadius = 0.01f, kSupport = 4.0f * kRadius, kVolume = 8.0f * kRadius * kRadius * kRadius;

struct OneParticle {
  Boundary boundary;
  Particles particles;
  NeighbourGrid grid;
  Neighbourhoods nb;
  CubicSpline kernel{kSupport};
};

// One fluid particle at x among `solids`, each placed as it is (a dynamic one at its centre).
void build(OneParticle& s, const std::vector<Solid>& solids, const Vec3f& x) {
  s.boundary = sample_boundary(SolidSet(solids), 2.0f * kRadius, kSupport);
  std::vector<SolidPlacement> placements(solids.size());
  for (size_t k = 0; k < solids.size(); ++k)
    if (solids[k].dynamics.enabled) placements[k].body = true, placements[k].translation = solids[k].centre();
  place_boundary(s.boundary, placements, true);
  s.particles.resize(1);
  s.particles.x = {x};
  s.particles.v = {Vec3f::Zero()};
  s.particles.id = {0};
  s.grid.build(s.particles.x, kSupport);
  s.particles.reorder(s.grid.sorted_to_original());
  build_neighbourhoods(s.grid, s.boundary, s.kernel, kVolume, s.particles, s.nb);
}

// alpha of a particle inside unbounded fluid on the lattice of spacing 2r: the pulls cancel, so it is
// 1 / sum_j |V grad W_ij|^2 over the lattice points within h.
float bulk_factor() {
  const CubicSpline kernel{kSupport};
  double sum = 0.0;
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j)
      for (int k = -3; k <= 3; ++k) {
        const Vec3f d = 2.0f * kRadius * Vec3f(float(i), float(j), float(k));
        const float r = d.norm();
        if ((i | j | k) == 0 || r > kSupport) continue;
        sum += double((kVolume * kernel.grad_factor(r) * d).squaredNorm());
      }
  return float(1.0 / sum);
}

Solid light_box(const Vec3f& lo, const Vec3f& hi, bool dynamic) {
  Solid b = testing::box_solid(lo, hi);
  b.dynamics.enabled = dynamic;
  b.dynamics.density = 700.0f;
  return b;
}

// Two boxes 0.2 m wide face to face across 0.7 of a particle's width, the particle a tenth of r off
// the gap's middle (exactly in the middle the pulls cancel to rounding).
std::vector<Solid> two_boxes(bool dynamic, float& middle) {
  const float gap = 1.4f * kRadius;
  middle = 0.5f * gap;
  return {light_box(Vec3f(-0.2f, -0.1f, -0.1f), Vec3f(0.0f, 0.1f, 0.1f), dynamic),
          light_box(Vec3f(gap, -0.1f, -0.1f), Vec3f(gap + 0.2f, 0.1f, 0.1f), dynamic)};
}

TEST(FluidBodyGap, AParticleBetweenTwoBodiesGetsNoMorePressurePerCompressionThanOneInBulk) {
  float middle;
  const std::vector<Solid> boxes = two_boxes(true, middle);
  OneParticle s;
  build(s, boxes, Vec3f(middle + 0.1f * kRadius, 0, 0));
  ASSERT_GT(s.nb.boundary_offset[1], 0u);
  const float bulk = bulk_factor();
  // Both faces' two layers lie within h: the boundary stands in for a full neighbourhood, less the
  // gap's slab, so the factor is the bulk's or a little more (1.4 times); before, 52 times.
  EXPECT_GT(s.particles.factor[0], 0.5f * bulk);
  EXPECT_LT(s.particles.factor[0], 2.0f * bulk);
}

// Static walls do not move, so the same gap between two static boxes keeps the factor from the
// fluid neighbours (here none) and the total pull alone: 1 / |sum_b V_b grad W_ib|^2, summed here
// over the boundary particles within h.
TEST(FluidBodyGap, StaticWallsCountOnlyInTheTotalPull) {
  float middle;
  const std::vector<Solid> boxes = two_boxes(false, middle);
  OneParticle s;
  const Vec3f x(middle + 0.1f * kRadius, 0, 0);
  build(s, boxes, x);
  Vec3f pull = Vec3f::Zero();
  const std::span<const Vec3f> points = s.boundary.grid.sorted_points();
  for (size_t k = 0; k < points.size(); ++k) {
    const Vec3f d = x - points[k];
    if (d.norm() <= kSupport) pull += s.boundary.sorted_volume[k] * s.kernel.grad_factor(d.norm()) * d;
  }
  ASSERT_GT(pull.squaredNorm(), 0.0f);
  EXPECT_NEAR(s.particles.factor[0], 1.0f / pull.squaredNorm(), 1e-4f / pull.squaredNorm());
  EXPECT_GT(s.particles.factor[0], 10.0f * bulk_factor());
}

}  // namespace
}  // namespace spume::fluid
