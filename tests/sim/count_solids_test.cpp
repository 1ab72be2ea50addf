// diffuse.count_solids switches the wet-wall count of the classification (MODEL.md §8.11) only: the
// surface test sees the solids either way (§8.10), so the fluid layer against a wall never forms a
// crest, as the key's doc says.
#include <gtest/gtest.h>

#include "sim/diffuse/simulator.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

constexpr float kR = 0.02f;

// A pool 0.2 m deep filling a 0.4 m tank, pressing on its x = 0.4 wall at 1.5 m/s (stored velocity;
// it cannot move, so its motion is zero). Against the wall its layer has no normal: no crest. Were the
// wall not seen by the surface test, that layer would be a face whose normal (+x) is the velocity's
// direction, with convex edges at the top and the side walls: crests (the control below).
uint64_t crest_emission(bool count_solids, bool with_tank) {
  DiffuseSetup s;
  s.fluid.particle_radius = kR;
  s.fluid.support_radius = 4 * kR;
  s.fluid.fps = 50.0;
  if (with_tank) {
    Solid tank;
    tank.kind = Solid::Kind::Tank;
    tank.min = Vec3f::Zero(), tank.max = Vec3f::Constant(0.4f);
    s.solids = SolidSet({tank});
  }
  s.params.count_solids = count_solids;
  s.params.k_ta = 0.0f, s.params.k_wc = 1000.0f;
  s.params.wave_crest = {0.05f, 0.5f};   // low: any convex edge would count
  s.params.kinetic = {1e-4f, 1e-3f};     // 0.5 x 0.064 kg x 1.5^2 = 0.072 J: I_k = 1
  DiffuseSimulator sim(s);
  const auto pool = testing::lattice(Vec3f::Constant(kR), Vec3f(0.4f - kR, 0.2f - kR, 0.4f - kR), 2 * kR);
  const std::vector<Vec3f> pressing(pool.size(), Vec3f(1.5f, 0, 0));
  const FluidFrame a = testing::frame_of(0, 0.0, pool, pressing), b = testing::frame_of(1, 0.02, pool, pressing);
  sim.process_frame(a, &b, [](const DiffuseFrame&, const FrameStats&) {});
  return sim.process_frame(b, nullptr, [](const DiffuseFrame&, const FrameStats&) {}).generated;
}

TEST(CountSolids, OffTheLayerAgainstAWallStillFormsNoCrest) {
  EXPECT_EQ(crest_emission(false, true), 0u);
  EXPECT_EQ(crest_emission(true, true), 0u);
  // The control: the same pool without its tank has a free face there, and it emits.
  EXPECT_GT(crest_emission(false, false), 100u);
}

}  // namespace
}  // namespace spume
