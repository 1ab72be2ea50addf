// Boundary particles: a fluid lattice resting against the walls reads rest density everywhere, and
// the sampled solid volumes add up to the solid volumes they stand for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "sim/fluid/boundary.h"
#include "sim/fluid/solver.h"

namespace spume {
namespace {

TEST(FluidBoundary, LatticeAgainstWallsReadsRestDensity) {
  // A closed tank exactly filled: every particle, at faces, edges and corners, should read rho0,
  // as the wall layers continue the fluid lattice (the lattice sum is 1, FluidKernel test).
  FluidSolverParams p;
  p.particle_radius = 0.01f;
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(0, 0, 0);
  tank.max = Vec3f(0.2f, 0.16f, 0.12f);
  tank.open_top = false;
  const FluidSolver solver(p, {FluidBlock{tank.min, tank.max}}, SolidSet({tank}));
  ASSERT_EQ(solver.size(), size_t(10 * 8 * 6));
  const std::vector<float> rho = solver.density_ratios();
  const auto [lo, hi] = std::minmax_element(rho.begin(), rho.end());
  EXPECT_NEAR(*lo, 1.0f, 2e-3f);
  EXPECT_NEAR(*hi, 1.0f, 2e-3f);
}

TEST(FluidBoundary, SampledVolumesAddUpToTheSolidLayers) {
  const float s = 0.02f, h = 0.04f;  // spacing 2r, support 4r: two layers
  {
    std::vector<Vec3f> pts;
    float cell = 0.0f;
    fluid::sample_box_layers(Vec3f(0, 0, 0), Vec3f(0.3f, 0.2f, 0.1f), s, 2, pts, cell);
    // A 15 x 10 x 5 cell box minus its 11 x 6 x 1 core.
    EXPECT_EQ(pts.size(), size_t(15 * 10 * 5 - 11 * 6 * 1));
    EXPECT_NEAR(cell, s * s * s, 1e-9f);
  }
  {
    std::vector<Vec3f> pts;
    float cell = 0.0f;
    fluid::sample_tank_walls(Vec3f(0, 0, 0), Vec3f(0.2f, 0.2f, 0.2f), s, 2, 1, pts, cell);
    // Open top: (10+4) x (10+2) x (10+4) padded lattice minus the 10 x 10 x 10 interior.
    EXPECT_EQ(pts.size(), size_t(14 * 12 * 14 - 1000));
    for (const Vec3f& q : pts) EXPECT_LT(q.y(), 0.2f);
  }
  {
    std::vector<Vec3f> pts;
    std::vector<float> vol;
    const float R = 0.15f;
    fluid::sample_sphere_layers(Vec3f(1, 2, 3), R, s, 2, pts, vol);
    const double shell = 4.0 / 3.0 * std::numbers::pi * (std::pow(R, 3) - std::pow(R - 2 * s, 3));
    EXPECT_NEAR(std::accumulate(vol.begin(), vol.end(), 0.0), shell, 1e-6 * shell + 1e-9);
    for (const Vec3f& q : pts) {
      const float d = (q - Vec3f(1, 2, 3)).norm();
      EXPECT_TRUE(std::abs(d - (R - 0.5f * s)) < 1e-4f || std::abs(d - (R - 1.5f * s)) < 1e-4f) << d;
    }
  }
  (void)h;
}

}  // namespace
}  // namespace spume
