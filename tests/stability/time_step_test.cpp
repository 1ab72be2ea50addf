// Diffuse time steps from 1/1000 s to a whole 1/24 s frame, fluid speeds from 1 to 1000 m/s: every
// value stays finite, every particle inside the domain, and the particle count within what Eq. 8 can
// ask for (memory bounded).
#include <gtest/gtest.h>

#include "tests/stability/stability_support.h"

namespace spume {
namespace {

struct Case {
  float speed;  // m/s
  double dt;    // s between frames
};

// Runs colliding blocks (r = 0.02 m) at the case's speed and frame step and checks the run.
void run_case(const Case& c, int frames, float side, int substeps) {
  SCOPED_TRACE(str("speed ", c.speed, " m/s, frame step ", c.dt, " s, substeps ", substeps));
  const float r = 0.02f;
  const auto fluid = stability::colliding_blocks(r, side, c.speed, c.dt, frames);
  DiffuseSetup setup = stability::setup_with(r, {{"substeps", substeps}}, 1.0 / c.dt);
  setup.domain.min = Vec3f(-3, -3, -3), setup.domain.max = Vec3f(3, 3, 3);
  const DiffuseParams& p = setup.params;
  DiffuseSimulator sim(setup);
  const auto run = stability::run_checked(sim, fluid);
  // Eq. 8 asks at most (k_ta + k_wc) dt per fluid particle and step (the potentials are clamped to
  // [0, 1]); stochastic rounding adds at most one.
  const double per_step = double(fluid[0].size()) * ((p.k_ta + p.k_wc) * c.dt / substeps + 1.0);
  EXPECT_LE(double(run.generated), per_step * substeps * (frames - 1));
  EXPECT_LE(double(run.max_particles), per_step * substeps * (frames - 1));
  EXPECT_GT(run.generated, 0u);  // the collision does emit
}

TEST(StabilityTimeStep, ExtremeStepsAndSpeeds) {
  for (float speed : {1.0f, 1000.0f})
    for (double dt : {1.0 / 1000, 1.0 / 24}) run_case({speed, dt}, 4, 0.16f, 1);
}

TEST(StabilityTimeStep, EveryStepAndSpeedFull) {
  for (float speed : {1.0f, 10.0f, 100.0f, 1000.0f})
    for (double dt : {1.0 / 1000, 1.0 / 240, 1.0 / 50, 1.0 / 24})
      for (int substeps : {1, 8}) run_case({speed, dt}, 12, 0.3f, substeps);
}

// A fast fluid leaves the domain within a frame: its diffuse particles are removed, not kept
// somewhere far away.
TEST(StabilityTimeStep, ThousandMetresPerSecondLeavesTheDomainClean) {
  const float r = 0.02f;
  const auto fluid = stability::translating_block(Vec3f(0, 0, 0), Vec3f(0.3f, 0.3f, 0.3f), r, Vec3f(1000, 0, 0),
                                                  1.0 / 24, 4);
  DiffuseSetup setup = stability::setup_with(r, Json::object(), 24.0);
  setup.domain.min = Vec3f(-1, -1, -1), setup.domain.max = Vec3f(1, 1, 1);
  DiffuseSimulator sim(setup);
  std::vector<Vec3f> start;
  for (int i = 0; i < 10; ++i) start.push_back(Vec3f(0.03f * i, 0.15f, 0.15f));
  sim.set_particles(stability::diffuse_at(start, DiffuseType::Foam, Vec3f(1000, 0, 0)));
  const auto run = stability::run_checked(sim, fluid);
  // Foam carries the fluid's 1000 m/s: 41.7 m in the first frame, far past x = 1.
  EXPECT_GE(run.removed, 10u);
}

}  // namespace
}  // namespace spume
