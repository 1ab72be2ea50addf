// The up axis measured from a cache's frames (io/up_axis_measure.h), on frames built by hand: a block
// falling freely (centroid z(t) = z0 - g t^2 / 2, so its second difference over dt is exactly -g dt^2),
// a block pushed apart (its shape changes), a pool at rest and a quasi-2D slab.
#include <gtest/gtest.h>

#include "sim/io/up_axis_measure.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

constexpr float kR = 0.02f;
constexpr double kFps = 25.0;

FluidFrame block_at(const Vec3f& lo, const Vec3f& size) {
  FluidFrame f;
  f.positions = testing::lattice(lo, lo + size + Vec3f::Constant(kR), 2.0f * kR);  // kR: past rounding
  return f;
}

// Frames 1..3 of a 0.28 m block accelerating at `a` (m/s^2) from rest.
std::vector<FluidFrame> accelerating(const Vec3f& a) {
  std::vector<FluidFrame> frames;
  for (int k = 1; k <= 3; ++k) {
    const float t = float(k - 1) / float(kFps);
    frames.push_back(block_at(Vec3f(0, 1, 1) + 0.5f * a * t * t, Vec3f::Constant(0.28f)));
  }
  return frames;
}

TEST(UpAxisMeasure, AFreeFallAlongMinusZSaysZ) {
  const UpAxisMeasure m = measure_up_axis(accelerating(Vec3f(0, 0, -9.81f)), {1, 2, 3}, kFps, kR);
  EXPECT_EQ(m.axis, 2);
  EXPECT_EQ(m.sign, 1);
  EXPECT_TRUE(m.by_fall);
  EXPECT_NE(m.how.find("accelerates at 9.8"), std::string::npos) << m.how;  // float positions near z = 1: 9.8x
  EXPECT_NE(m.how.find(" m/s^2 toward -z"), std::string::npos) << m.how;
}

TEST(UpAxisMeasure, AFallTowardPlusYSaysYUpsideDown) {
  const UpAxisMeasure m = measure_up_axis(accelerating(Vec3f(0, 9.81f, 0)), {1, 2, 3}, kFps, kR);
  EXPECT_EQ(m.axis, 1);
  EXPECT_EQ(m.sign, -1);
}

TEST(UpAxisMeasure, ABlockThatChangesShapeOrMovesSteadilyIsNoFall) {
  // Two blocks pushed apart along x at 1 m/s each and accelerating at g along -z: the shape grows 8 cm a
  // frame along x (more than 2 r), so something pushes: no fall.
  std::vector<FluidFrame> frames;
  for (int k = 1; k <= 3; ++k) {
    const float t = float(k - 1) / float(kFps);
    FluidFrame a = block_at(Vec3f(-t, 0, 1 - 4.905f * t * t), Vec3f::Constant(0.2f));
    const FluidFrame b = block_at(Vec3f(1 + t, 0, 1 - 4.905f * t * t), Vec3f::Constant(0.2f));
    a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
    frames.push_back(a);
  }
  EXPECT_EQ(measure_up_axis(frames, {1, 2, 3}, kFps, kR).axis, -1);
  // Moving at a constant 1 m/s: no acceleration (below g / 10).
  EXPECT_EQ(measure_up_axis(accelerating(Vec3f::Zero()), {1, 2, 3}, kFps, kR).axis, -1);
}

TEST(UpAxisMeasure, APoolAtRestIsALayerAndASlabOfOneParticleIsNot) {
  const FluidFrame pool = block_at(Vec3f::Zero(), Vec3f(1.2f, 0.8f, 0.24f));
  const UpAxisMeasure m = measure_up_axis({pool, pool, pool, pool}, {1, 2, 3, 10}, kFps, kR);
  EXPECT_EQ(m.axis, 2);
  EXPECT_FALSE(m.by_fall);
  EXPECT_NE(m.how.find("frame 10 is a layer 0.24 m thick along z and 1.2 x 0.8 m across"), std::string::npos) << m.how;
  // Quasi-2D: 3 particles (0.08 m, under 8 r = 0.16 m) across z: not a layer gravity made.
  const FluidFrame slab = block_at(Vec3f::Zero(), Vec3f(1.2f, 0.8f, 0.08f));
  EXPECT_EQ(measure_up_axis({slab, slab, slab}, {1, 2, 3}, kFps, kR).axis, -1);
  // A cube is no layer.
  const FluidFrame cube = block_at(Vec3f::Zero(), Vec3f::Constant(0.4f));
  EXPECT_EQ(measure_up_axis({cube, cube, cube}, {1, 2, 3}, kFps, kR).axis, -1);
}

}  // namespace
}  // namespace spume
