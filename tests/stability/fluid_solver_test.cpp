// The fluid solver on stiff cases: a 10 m water column (hydrostatic pressure 1e5 Pa at the floor), a
// dam break with no viscosity at all and a tight density tolerance, and a time step at the CFL limit
// (a particle may cross its own diameter in a step). Each run stays finite and inside the tank, no
// particle runs faster than 1.5 x the Ritter dam-break front 2 sqrt(g H) (the fastest flow a collapsing
// column makes: pressure hands the front more than its own fall), and the mechanical energy never
// grows (nothing drives it).
#include <gtest/gtest.h>

#include <cmath>

#include "sim/core/error.h"
#include "sim/fluid/solver.h"
#include "tests/stability/fluid_run_checks.h"

namespace spume {
namespace {

using stability::run_checked;
using stability::tank_of;

void water_column(double seconds) {
  // 10 m of water, 0.6 m square, r = 0.1 m: 3 x 50 x 3 = 450 particles.
  FluidSolverParams p;
  p.particle_radius = 0.1f;
  const Solid tank = tank_of(Vec3f(0, 0, 0), Vec3f(0.6f, 12, 0.6f));
  FluidSolver solver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(0.6f, 10, 0.6f)}}, SolidSet({tank}));
  ASSERT_EQ(solver.size(), 450u);
  run_checked(solver, tank, seconds, 10.0);
  const SolverStats s = solver.stats();
  EXPECT_LT(s.max_density_error, 0.01);  // 1% average compression under 1e5 Pa, even if a solve gave up
  // A column at rest stays a column: its top stays near 10 m (the lattice compacts a little).
  float top = 0.0f;
  for (const Vec3f& x : solver.frame(0).positions) top = std::max(top, x.y());
  EXPECT_GT(top, 9.0f);  // settles by at most 10% (a collapse would drop it to the floor)
  EXPECT_LT(top, 10.0f);
}

TEST(StabilityFluidSolver, TenMetreWaterColumn) { water_column(0.2); }
TEST(StabilityFluidSolver, TenMetreWaterColumnFull) { water_column(2.0); }

void dam_break(FluidSolverParams p, double seconds) {
  // 0.4 x 0.4 x 0.2 m of water at r = 0.02 m (10 x 10 x 5 = 500 particles) released in a 1.2 m long tank.
  p.particle_radius = 0.02f;
  const Solid tank = tank_of(Vec3f(0, 0, 0), Vec3f(1.2f, 1.5f, 0.2f));
  FluidSolver solver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(0.4f, 0.4f, 0.2f)}}, SolidSet({tank}));
  ASSERT_EQ(solver.size(), 500u);
  run_checked(solver, tank, seconds, 0.4);
  const SolverStats s = solver.stats();
  EXPECT_GT(s.steps, 0u);
  EXPECT_LT(s.max_density_error, 0.05);  // never 5% compressed on average, even when a solve gave up
  const double front = [&] {
    float x = 0.0f;
    for (const Vec3f& q : solver.frame(0).positions) x = std::max(x, q.x());
    return x;
  }();
  EXPECT_GT(front, 0.45);  // the column did collapse and run
}

FluidSolverParams inviscid_stiff() {
  FluidSolverParams p;
  p.viscosity = 0.0f;
  p.boundary_viscosity = 0.0f;
  p.density_tolerance = 1e-4f;
  p.divergence_tolerance = 1e-4f;
  p.max_density_iterations = 200;
  return p;
}

FluidSolverParams at_cfl_limit() {
  FluidSolverParams p;
  p.cfl = 1.0f;       // a particle crosses its diameter 2r in one step
  p.max_dt = 0.02;    // so that the CFL condition, not max_dt or the depth, sets the step
  p.depth_cfl = 0.0f;
  return p;
}

TEST(StabilityFluidSolver, InviscidStiffDamBreak) { dam_break(inviscid_stiff(), 0.3); }
TEST(StabilityFluidSolver, InviscidStiffDamBreakFull) { dam_break(inviscid_stiff(), 1.5); }
TEST(StabilityFluidSolver, TimeStepAtTheCflLimit) { dam_break(at_cfl_limit(), 0.3); }
TEST(StabilityFluidSolver, TimeStepAtTheCflLimitFull) { dam_break(at_cfl_limit(), 1.5); }

TEST(StabilityFluidSolver, UnreasonableSettingsAreRefused) {
  const Solid tank = tank_of(Vec3f(0, 0, 0), Vec3f(1, 1, 1));
  const FluidBlock block{Vec3f(0, 0, 0), Vec3f(0.2f, 0.2f, 0.2f)};
  auto refused = [&](FluidSolverParams p, const char* key) {
    try {
      FluidSolver solver(p, {block}, SolidSet({tank}));
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
      return;
    }
    ADD_FAILURE() << key << " was accepted";
  };
  FluidSolverParams p;
  p.cfl = 0.0f;
  refused(p, "cfl");
  p = {};
  p.min_dt = 0.1, p.max_dt = 0.01;
  refused(p, "min_dt");
  p = {};
  p.viscosity = -1.0f;
  refused(p, "viscosity");
  p = {};
  p.particle_radius = NAN;
  refused(p, "particle_radius");
}

}  // namespace
}  // namespace spume
