// Frame pairing and interpolation (diffuse/fluid_state.h) on small frames worked by hand: the join on
// particle id, particles that vanish, frames without ids, velocities or masses.
#include <gtest/gtest.h>

#include "sim/diffuse/fluid_state.h"

namespace spume {
namespace {

FluidFrame frame(double time, std::vector<Vec3f> x, std::vector<uint32_t> ids, std::vector<Vec3f> v = {}) {
  FluidFrame f;
  f.time = time;
  f.positions = std::move(x);
  f.ids = std::move(ids);
  f.velocities = std::move(v);
  return f;
}

TEST(PairFrames, JoinsOnIdWhateverTheOrderAndMarksVanishedParticles) {
  // Ids 10, 20, 30, 40 at frame k; at k+1 particle 20 is gone, 50 is new and the order is shuffled.
  const FluidFrame a = frame(0.0, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, {10, 20, 30, 40});
  const FluidFrame b = frame(0.1, {{3, 1, 0}, {0, 1, 0}, {9, 9, 9}, {2, 1, 0}}, {40, 10, 50, 30});
  const FramePair pair = pair_frames(a, &b, 0.1);
  EXPECT_EQ(pair.next_index, (std::vector<int32_t>{1, -1, 3, 0}));
  EXPECT_EQ(pair.current, &a);
  EXPECT_EQ(pair.next, &b);
  EXPECT_EQ(pair.frame_dt, 0.1);
}

TEST(PairFrames, WithoutIdsParticlesArePairedByIndex) {
  // No ids: particle i is particle i; a frame that lost its last particle leaves that one unmatched.
  const FluidFrame a = frame(0.0, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {});
  const FluidFrame same = frame(0.1, {{0, 1, 0}, {1, 1, 0}, {2, 1, 0}}, {});
  EXPECT_EQ(pair_frames(a, &same, 0.1).next_index, (std::vector<int32_t>{0, 1, 2}));
  const FluidFrame fewer = frame(0.1, {{0, 1, 0}, {1, 1, 0}}, {});
  EXPECT_EQ(pair_frames(a, &fewer, 0.1).next_index, (std::vector<int32_t>{0, 1, -1}));
  // The last frame pairs with nothing.
  EXPECT_EQ(pair_frames(a, nullptr, 0.0).next_index, (std::vector<int32_t>{-1, -1, -1}));
}

TEST(InterpolateFluid, MatchedParticlesMoveLinearlyAndVanishedOnesWithTheirVelocity) {
  // dt = 0.1 s, s = 0.25. Particle 10: (0,0,0) -> (0,1,0), stored velocities (0,8,0) -> (0,12,0):
  //   x = (0, 0.25, 0), motion = (0, 10, 0), v = 8 + 0.25 (12 - 8) = 9 along y.
  // Particle 20 has no partner: x = (1,0,0) + 0.25 0.1 (2,0,0) = (1.05,0,0), motion = v = (2,0,0).
  const FluidFrame a = frame(0.0, {{0, 0, 0}, {1, 0, 0}}, {10, 20}, {{0, 8, 0}, {2, 0, 0}});
  const FluidFrame b = frame(0.1, {{0, 1, 0}}, {10}, {{0, 12, 0}});
  const FramePair pair = pair_frames(a, &b, 0.1);
  FluidStepState s;
  interpolate_fluid(pair, 0.25f, 0.5f, s);
  ASSERT_EQ(s.positions.size(), 2u);
  EXPECT_NEAR((s.positions[0] - Vec3f(0, 0.25f, 0)).norm(), 0.0f, 1e-6f);
  EXPECT_NEAR((s.motion[0] - Vec3f(0, 10, 0)).norm(), 0.0f, 1e-5f);
  EXPECT_NEAR((s.velocities[0] - Vec3f(0, 9, 0)).norm(), 0.0f, 1e-5f);
  EXPECT_NEAR((s.positions[1] - Vec3f(1.05f, 0, 0)).norm(), 0.0f, 1e-6f);
  EXPECT_EQ(s.motion[1], Vec3f(2, 0, 0));
  EXPECT_EQ(s.velocities[1], Vec3f(2, 0, 0));
  EXPECT_EQ(s.ids, (std::vector<uint32_t>{10, 20}));
  EXPECT_EQ(s.masses, (std::vector<float>{0.5f, 0.5f}));  // no masses in the frame: the uniform mass
}

TEST(InterpolateFluid, WithoutStoredVelocitiesTheFrameDifferenceIsTheVelocity) {
  // Neither frame has velocities: v = motion = (x_b - x_a) / dt; the vanished particle has neither
  // and stays where it is. Only one frame with velocities: the difference too (a half-known v_f(t)
  // would mix two measures).
  const FluidFrame a = frame(0.0, {{0, 0, 0}, {5, 0, 0}}, {1, 2});
  const FluidFrame b = frame(0.5, {{1, 2, 0}}, {1});
  FluidStepState s;
  interpolate_fluid(pair_frames(a, &b, 0.5), 0.5f, 1.0f, s);
  EXPECT_NEAR((s.velocities[0] - Vec3f(2, 4, 0)).norm(), 0.0f, 1e-6f);
  EXPECT_EQ(s.velocities[0], s.motion[0]);
  EXPECT_NEAR((s.positions[0] - Vec3f(0.5f, 1, 0)).norm(), 0.0f, 1e-6f);
  EXPECT_EQ(s.velocities[1], Vec3f::Zero());
  EXPECT_EQ(s.motion[1], Vec3f::Zero());
  EXPECT_EQ(s.positions[1], Vec3f(5, 0, 0));

  const FluidFrame with_v = frame(0.0, {{0, 0, 0}}, {1}, {{7, 7, 7}});
  const FluidFrame without_v = frame(0.5, {{1, 2, 0}}, {1});
  interpolate_fluid(pair_frames(with_v, &without_v, 0.5), 0.0f, 1.0f, s);
  EXPECT_NEAR((s.velocities[0] - Vec3f(2, 4, 0)).norm(), 0.0f, 1e-6f);
}

TEST(InterpolateFluid, PerParticleMassesAreKept) {
  FluidFrame a = frame(0.0, {{0, 0, 0}, {1, 0, 0}}, {1, 2});
  a.masses = {0.25f, 0.75f};
  FluidStepState s;
  interpolate_fluid(pair_frames(a, nullptr, 0.0), 0.0f, 9.0f, s);
  EXPECT_EQ(s.masses, (std::vector<float>{0.25f, 0.75f}));
  EXPECT_EQ(s.positions[1], Vec3f(1, 0, 0));  // the last frame: nothing to move towards, no velocity
}

}  // namespace
}  // namespace spume
