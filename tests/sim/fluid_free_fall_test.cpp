// A block of fluid in free fall (no solids) feels no pressure: every particle follows gravity
// exactly, v = g t, and x = x0 + g t^2 / 2 up to the symplectic Euler error g t dt / 2.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/fluid/solver.h"

namespace spume {
namespace {

TEST(FluidFreeFall, BlockWithoutSolidsFollowsGravity) {
  FluidSolverParams p;
  p.particle_radius = 0.01f;
  p.gravity = Vec3f(0, 0, -9.81f);
  FluidSolver solver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(0.2f, 0.2f, 0.2f)}}, SolidSet{});
  const FluidFrame start = solver.frame(0);
  const double t = 0.3;
  solver.advance_to(t);
  const FluidFrame end = solver.frame(1);
  EXPECT_EQ(end.time, t);
  const double dt_max = p.max_dt;
  for (size_t i = 0; i < end.size(); ++i) {
    EXPECT_NEAR(end.velocities[i].z(), -9.81 * t, 1e-4);
    EXPECT_NEAR(end.velocities[i].x(), 0.0, 1e-6);
    const double fall = start.positions[i].z() - end.positions[i].z();
    EXPECT_NEAR(fall, 0.5 * 9.81 * t * t, 0.5 * 9.81 * t * dt_max + 1e-5);
    EXPECT_NEAR(end.positions[i].x(), start.positions[i].x(), 1e-6);
  }
  EXPECT_EQ(solver.stats().corrections, 0u);
}

}  // namespace
}  // namespace spume
