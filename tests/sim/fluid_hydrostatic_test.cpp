// A tank of water at rest must stay at rest: density within the solver's bound, velocities decaying,
// the centre of mass settling and then staying put, nothing leaving the tank.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/fluid/solver.h"

namespace spume {
namespace {

struct Snapshot {
  Vec3d com = Vec3d::Zero();
  double max_speed = 0.0, rms_speed = 0.0;
};

Snapshot measure(const FluidFrame& f) {
  Snapshot s;
  for (size_t i = 0; i < f.size(); ++i) {
    s.com += f.positions[i].cast<double>();
    const double v = f.velocities[i].norm();
    s.max_speed = std::max(s.max_speed, v);
    s.rms_speed += v * v;
  }
  s.com /= double(f.size());
  s.rms_speed = std::sqrt(s.rms_speed / double(f.size()));
  return s;
}

TEST(FluidHydrostatic, TankAtRestKeepsDensityAndStaysStill) {
  // 0.4 x 0.4 x 0.2 m of water (20 x 20 x 10 = 4000 particles, r = 1 cm) in an open tank.
  FluidSolverParams p;
  p.particle_radius = 0.01f;
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(0, 0, 0);
  tank.max = Vec3f(0.4f, 0.6f, 0.2f);
  const FluidBlock water{Vec3f(0, 0, 0), Vec3f(0.4f, 0.4f, 0.2f)};
  FluidSolver solver(p, {water}, SolidSet({tank}));
  ASSERT_EQ(solver.size(), 4000u);
  const double com0 = 0.2;  // the block's centre height, m

  Snapshot at_half, at_end, at_03;
  for (int frame = 1; frame <= 50; ++frame) {  // 1 s at 50 fps
    solver.advance_to(frame * 0.02);
    const FluidFrame f = solver.frame(frame);
    for (const Vec3f& x : f.positions) {  // nothing leaves the tank (the top is open: no upper bound)
      ASSERT_GE(x.x(), tank.min.x());
      ASSERT_LE(x.x(), tank.max.x());
      ASSERT_GE(x.y(), tank.min.y());
      ASSERT_GE(x.z(), tank.min.z());
      ASSERT_LE(x.z(), tank.max.z());
    }
    if (frame == 15) at_03 = measure(f);
    if (frame == 25) at_half = measure(f);
    if (frame == 50) at_end = measure(f);
  }
  const SolverStats st = solver.stats();
  // Density: every step's solve met the 0.05% average bound.
  EXPECT_LE(st.max_density_error, p.density_tolerance);
  EXPECT_EQ(st.density_unconverged, 0u);
  // Interior particles (full neighbourhoods) sit at rest density.
  const std::vector<float> rho = solver.density_ratios();
  const FluidFrame f = solver.frame(50);
  double sum = 0.0;
  int count = 0;
  for (size_t i = 0; i < rho.size(); ++i)
    if (f.positions[i].y() < 0.25f) sum += rho[i], ++count;
  EXPECT_NEAR(sum / count, 1.0, 2e-3);

  // Velocities decay: a 0.4 m column has a velocity scale sqrt(g H) ~ 2 m/s.
  EXPECT_LT(at_end.max_speed, 0.15);
  EXPECT_LT(at_end.rms_speed, 0.5 * at_03.rms_speed);
  EXPECT_LT(at_end.rms_speed, 0.03);
  // The centre of mass: no horizontal drift; the initial lattice compacts once (the surface layer and
  // the disordered packing, measured ~2.6% of the height), then the fluid stays put.
  EXPECT_NEAR(at_end.com.x(), 0.2, 1e-3);
  EXPECT_NEAR(at_end.com.z(), 0.1, 1e-3);
  EXPECT_GT(at_end.com.y(), 0.96 * com0);
  EXPECT_LT(at_end.com.y(), com0 + 1e-3);
  EXPECT_NEAR(at_end.com.y(), at_half.com.y(), 1e-3);
  // Projections out of solids are rare (none expected at rest).
  EXPECT_LE(st.corrections, 10u);
  std::printf("[hydrostatic] steps %llu, avg dt %.4f s, avg iterations %.1f (density) %.1f (divergence), "
              "max avg density error %.5f, interior rho/rho0 %.5f, max |v| %.4f m/s, rms %.4f m/s, "
              "COM height %.5f -> %.5f -> %.5f m, corrections %llu\n",
              (unsigned long long)st.steps, st.average_dt, st.average_density_iterations,
              st.average_divergence_iterations, st.max_density_error, sum / count, at_end.max_speed,
              at_end.rms_speed, com0, at_half.com.y(), at_end.com.y(), (unsigned long long)st.corrections);
}

}  // namespace
}  // namespace spume
