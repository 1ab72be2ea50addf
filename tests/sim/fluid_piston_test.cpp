// A kinematic wave-maker: a box piston oscillating into the fluid never contains fluid particles, the
// projections that guarantee it are rare, and the fluid is pushed the way the piston moves.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/fluid/solver.h"

namespace spume {
namespace {

TEST(FluidPiston, KinematicPistonNeverContainsFluid) {
  FluidSolverParams p;
  p.particle_radius = 0.01f;
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(0, 0, 0);
  tank.max = Vec3f(0.8f, 0.4f, 0.1f);
  Solid piston;
  piston.kind = Solid::Kind::Box;
  piston.min = Vec3f(0.0f, 0.0f, 0.0f);
  piston.max = Vec3f(0.06f, 0.4f, 0.1f);
  piston.motion.kind = Motion::Kind::Sine;  // x offset 0.06 sin(2 pi t): 0.38 m/s at most
  piston.motion.axis = Vec3f::UnitX();
  piston.motion.amplitude = 0.06f;
  piston.motion.frequency = 1.0f;
  const FluidBlock water{Vec3f(0.1f, 0, 0), Vec3f(0.8f, 0.2f, 0.1f)};
  FluidSolver solver(p, {water}, SolidSet({tank, piston}));
  ASSERT_EQ(solver.size(), 35u * 10u * 5u);

  auto com_x = [&] {
    const FluidFrame f = solver.frame(0);
    double c = 0.0;
    for (const Vec3f& x : f.positions) c += x.x();
    return c / double(f.size());
  };
  const double com_start = com_x();
  double com_quarter = 0.0;
  uint64_t checked = 0;
  while (solver.time() < 1.0) {
    solver.advance_to(std::min(1.0, solver.time() + 0.005));
    const SolidSet now = solver.solids().at_time(solver.time());
    const FluidFrame f = solver.frame(0);
    for (size_t i = 0; i < f.size(); ++i) ASSERT_FALSE(now.inside(f.positions[i])) << "t = " << solver.time();
    checked += f.size();
    if (com_quarter == 0.0 && solver.time() >= 0.25) com_quarter = com_x();
  }
  const SolverStats st = solver.stats();
  // The piston advanced 6 cm in the first quarter period: the water moved with it.
  EXPECT_GT(com_quarter - com_start, 0.002);
  EXPECT_LE(st.corrections, st.steps * solver.size() / 1000);
  EXPECT_LE(st.max_density_error, p.density_tolerance);
  std::printf("[piston] steps %llu, corrections %llu of %llu particle-steps, COM x %+.4f m after 1/4 period\n",
              (unsigned long long)st.steps, (unsigned long long)st.corrections,
              (unsigned long long)(st.steps * solver.size()), com_quarter - com_start);
  (void)checked;
}

}  // namespace
}  // namespace spume
