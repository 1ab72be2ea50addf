// Frame pairing and interpolation (diffuse/fluid_state.h) on small frames worked by hand: the join on
// particle id, particles that vanish, frames without ids (kept order, reordered, growing), velocities
// or masses.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

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

// A 4 x 4 x 4 lattice at spacing 0.1 m (x fastest, then y, then z), without ids, and where it is
// dt = 0.1 s later after falling 0.05 m at 0.5 m/s.
constexpr double kDt = 0.1;
std::vector<Vec3f> lattice(float y_shift) {
  std::vector<Vec3f> x;
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) x.push_back(Vec3f(0.1f * i, 0.1f * j + y_shift, 0.1f * k));
  return x;
}
std::vector<Vec3f> falling(size_t n) { return std::vector<Vec3f>(n, Vec3f(0.0f, -0.5f, 0.0f)); }

TEST(PairFrames, WithoutIdsAKeptIndexOrderIsPairedByIndex) {
  const FluidFrame a = frame(0.0, lattice(0.0f), {}, falling(64));
  const FluidFrame b = frame(kDt, lattice(-0.05f), {}, falling(64));
  std::vector<int32_t> identity(64);
  std::iota(identity.begin(), identity.end(), 0);
  const FramePair pair = pair_frames(a, &b, kDt);
  EXPECT_EQ(pair.next_index, identity);
  EXPECT_EQ(pair.unpaired_because, "");
  // Without stored velocities: each particle lands 0.05 m from where it was, against 0.2 m between
  // particle i and i + 32 (two layers apart in z): the order is kept.
  const FluidFrame a_bare = frame(0.0, lattice(0.0f), {});
  const FluidFrame b_bare = frame(kDt, lattice(-0.05f), {});
  EXPECT_EQ(pair_frames(a_bare, &b_bare, kDt).next_index, identity);
  // The last frame pairs with nothing, and that needs no reason.
  const FramePair last = pair_frames(a, nullptr, 0.0);
  EXPECT_EQ(last.next_index, std::vector<int32_t>(64, -1));
  EXPECT_EQ(last.unpaired_because, "");
}

TEST(PairFrames, WithoutIdsAReorderedFrameIsNotPairedAndMovesWithItsVelocities) {
  // The next frame lists the same particles in reverse: index i lands on the particle mirrored through
  // the centre, 0.17-0.52 m from where particle i went (median over 0.3 m), against 0.2 m between
  // unrelated particles: nothing may be paired by index.
  const FluidFrame a = frame(0.0, lattice(0.0f), {}, falling(64));
  std::vector<Vec3f> reversed = lattice(-0.05f);
  std::reverse(reversed.begin(), reversed.end());
  const FluidFrame b = frame(kDt, reversed, {}, falling(64));
  const FramePair pair = pair_frames(a, &b, kDt);
  EXPECT_EQ(pair.next_index, std::vector<int32_t>(64, -1));
  EXPECT_NE(pair.unpaired_because.find("the index order changes"), std::string::npos) << pair.unpaired_because;
  // Halfway, every particle is where its own velocity puts it (paired by index, the reversed frame
  // would have put particle 0 halfway to the far corner).
  FluidStepState s;
  interpolate_fluid(pair, 0.5f, 1.0f, s);
  const std::vector<Vec3f> start = lattice(0.0f);
  for (size_t i = 0; i < 64; ++i) {
    EXPECT_NEAR((s.positions[i] - (start[i] + Vec3f(0.0f, -0.025f, 0.0f))).norm(), 0.0f, 1e-6f) << i;
    EXPECT_NEAR((s.motion[i] - Vec3f(0.0f, -0.5f, 0.0f)).norm(), 0.0f, 1e-6f) << i;
  }
}

TEST(PairFrames, WithoutIdsAFrameWhoseCountChangesIsNotPaired) {
  // A growing sequence (a FLIP solver reseeding, an emitter): the first 64 particles keep their order
  // and 8 are appended, yet without ids index i is no evidence; nothing is paired and the log says why.
  const FluidFrame a = frame(0.0, lattice(0.0f), {}, falling(64));
  std::vector<Vec3f> grown = lattice(-0.05f);
  for (int i = 0; i < 8; ++i) grown.push_back(Vec3f(0.1f * i, 1.0f, 0.0f));
  const FluidFrame b = frame(kDt, grown, {}, falling(72));
  const FramePair pair = pair_frames(a, &b, kDt);
  EXPECT_EQ(pair.next_index, std::vector<int32_t>(64, -1));
  EXPECT_EQ(pair.unpaired_because, "the particle count changes (64 -> 72)");
  // A frame that lost particles is no different.
  const FluidFrame fewer = frame(kDt, std::vector<Vec3f>(grown.begin(), grown.begin() + 60), {}, falling(60));
  EXPECT_EQ(pair_frames(a, &fewer, kDt).unpaired_because, "the particle count changes (64 -> 60)");
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
