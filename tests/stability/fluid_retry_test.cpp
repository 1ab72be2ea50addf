// The solver takes a blown-up stretch again from its last good state with half the step (solver.h):
// a 10 m column told to step 160 ms settles on a shorter step and stands, the same bytes for any
// thread count; one whose smallest allowed step cannot cure it stops, saying what was tried.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "sim/core/parallel.h"
#include "sim/fluid/solver.h"
#include "tests/stability/fluid_run_checks.h"
#include "tests/support/error_of.h"

namespace spume {
namespace {

using testing::error_of;
using stability::tank_of;

const Solid kTank = tank_of(Vec3f(0, 0, 0), Vec3f(0.6f, 12, 0.6f));

// 10 m of water, 0.6 m square, r = 0.1 m (3 x 50 x 3 = 450 particles), every step at most `max_dt`
// s, with no depth limit: what depth_cfl allows it is 0.55 x 0.2 / sqrt(9.81 x 10) = 11.1 ms.
FluidSolver column(double max_dt, double min_dt = 1e-5) {
  FluidSolverParams p;
  p.particle_radius = 0.1f;
  p.max_dt = max_dt;
  p.min_dt = min_dt;
  p.depth_cfl = 0.0f;
  return FluidSolver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(0.6f, 10, 0.6f)}}, SolidSet({kTank}));
}

TEST(StabilityFluidRetry, TooLongAStepIsHalvedUntilTheRunIsHealthy) {
  FluidSolver solver = column(0.16);
  EXPECT_EQ(solver.stats().step_cap, 0.16);
  const stability::Energy start = stability::energy_of(solver.frame(0));
  solver.advance_to(2.0);  // one stretch: frames would cut the steps to their own length
  const SolverStats s = solver.stats();
  // No energy gained and no particle past 1.5 x Ritter's front (fluid_run_checks.h). The detector
  // lets through what stays within its bounds: at the 40 ms it settles on the column still sways at
  // up to 4 m/s, where the 11 ms depth_cfl gives calms it (MODEL.md §10).
  const FluidFrame end = solver.frame(1);
  EXPECT_LE(stability::energy_of(end).total(), start.total() + 0.05 * 9.81 * 10.0);
  for (const Vec3f& v : end.velocities) EXPECT_LT(v.norm(), 1.5 * 2.0 * std::sqrt(9.81 * 10.0));
  ASSERT_GE(s.retries, 1u);
  // Each retry at least halves the cap, and no step since went over it.
  EXPECT_LE(s.step_cap, 0.16 / double(uint64_t(1) << s.retries));
  EXPECT_LE(s.max_dt_used, 0.16);
  // A column at rest stays a column: its top stays above 9 m.
  float top = 0.0f;
  for (const Vec3f& x : solver.frame(0).positions) top = std::max(top, x.y());
  EXPECT_GT(top, 9.0f);
  EXPECT_NE(solver.last_retry_reason().find("blew up"), std::string::npos) << solver.last_retry_reason();
  std::printf("[retry] %llu retries, settled at %.4f ms, %llu steps\n", static_cast<unsigned long long>(s.retries),
              1e3 * s.step_cap, static_cast<unsigned long long>(s.steps));
}

// The same column with a cap of 1 s, but a box far outside the tank slides at 0.5 m/s, so the CFL
// condition keeps every step at 0.4 x 2r / 0.5 m/s = 0.16 s, the step that blew up above. Halving
// the cap alone took it through 0.5 and 0.25 s, retrying the very steps that blew up, and only the
// fourth retry (0.0625 s) stepped shorter than 0.16 s, and the run stopped there; halving the
// longest step taken goes to 0.08 s at once and settles as the column above does.
TEST(StabilityFluidRetry, ARetryStepsShorterThanTheStepsThatBlewUpWhateverTheCap) {
  FluidSolverParams p;
  p.particle_radius = 0.1f;
  p.max_dt = 1.0;
  p.depth_cfl = 0.0f;
  Solid box;
  box.kind = Solid::Kind::Box;
  box.min = Vec3f(5, 0, 0), box.max = Vec3f(5.4f, 0.4f, 0.4f);
  box.motion.kind = Motion::Kind::Keyframes;
  box.motion.times = {0.0, 10.0};
  box.motion.offsets = {Vec3f::Zero(), Vec3f(0, 0, 5)};
  FluidSolver solver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(0.6f, 10, 0.6f)}}, SolidSet({kTank, box}));
  solver.advance_to(2.0);
  const SolverStats s = solver.stats();
  ASSERT_GE(s.retries, 1u);
  EXPECT_LE(s.retries, 3u);
  EXPECT_LE(s.max_dt_used, 0.16 * 1.001);
  EXPECT_LE(s.step_cap, 0.08);
  float top = 0.0f;
  for (const Vec3f& x : solver.frame(0).positions) top = std::max(top, x.y());
  EXPECT_GT(top, 9.0f);
}

TEST(StabilityFluidRetry, RetriesGiveTheSameBytesForAnyThreadCount) {
  std::vector<Vec3f> x[2];
  uint64_t retries[2];
  for (int threads : {1, 2}) {
    set_thread_count(threads);
    FluidSolver solver = column(0.16);
    solver.advance_to(1.0);
    x[threads - 1] = solver.frame(0).positions;
    retries[threads - 1] = solver.stats().retries;
  }
  set_thread_count(0);
  EXPECT_GE(retries[0], 1u);
  EXPECT_EQ(retries[0], retries[1]);
  ASSERT_EQ(x[0].size(), x[1].size());
  EXPECT_EQ(std::memcmp(x[0].data(), x[1].data(), x[0].size() * sizeof(Vec3f)), 0);
}

TEST(StabilityFluidRetry, WhatCannotBeCuredStopsSayingWhatWasTried) {
  // Steps of at least 60 ms: the steps that blow up are halved to that floor, which blows up too.
  {
    FluidSolver solver = column(0.16, 0.06);
    const std::string e = error_of([&] { solver.advance_to(2.0); });
    for (const char* part : {"blew up", "taken again 1 time from t = 0 s with steps down to 0.06 s"})
      EXPECT_NE(e.find(part), std::string::npos) << part << " not in: " << e;
  }
  // Steps of at least 0.2 s from the start (the CFL step of a fall from rest is far shorter): a
  // retry could only take the same steps again, so there is none (before, three, all alike).
  {
    FluidSolver solver = column(1.0, 0.2);
    const std::string e = error_of([&] { solver.advance_to(2.0); });
    for (const char* part : {"blew up", "not taken again: its steps were already at fluid.solver.min_dt, 0.2 s"})
      EXPECT_NE(e.find(part), std::string::npos) << part << " not in: " << e;
    EXPECT_EQ(solver.stats().retries, 0u);
  }
}

}  // namespace
}  // namespace spume
