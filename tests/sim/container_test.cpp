// The container inferred from a fluid sequence (scene/container.h), on sequences built by hand whose
// walls are known: every wall the fluid was stopped at is found within r of its plane, and none is
// invented where the fluid touches nothing, stays at rest, or is pushed by a moving piston.
#include <gtest/gtest.h>

#include "tests/support/container_sequences.h"
#include "sim/scene/container.h"

namespace spume {
namespace {

using testing::kSeqRadius;

FluidSurvey survey_of(const std::vector<std::vector<Vec3f>>& frames, int first = 1) {
  FluidSurvey s;
  for (size_t k = 0; k < frames.size(); ++k) {
    FrameSurvey f = survey_positions(frames[k]);
    f.frame = first + int(k);
    s.frames.push_back(f);
  }
  return s;
}

constexpr int kY = 1;  // up axis
enum Side { MinusX, PlusX, MinusY, PlusY, MinusZ, PlusZ };

TEST(InferContainer, FindsEveryWallOfACollapsingColumnWithinR) {
  const Vec3f origin(5.0f, 2.0f, -3.0f);  // away from the origin: nothing is found at 0 by accident
  const InferredContainer c = infer_container(survey_of(testing::collapsing_column(origin)), kSeqRadius, kY);
  ASSERT_TRUE(c.tank) << c.summary;
  const Vec3f lo = origin + testing::kColumnTankMin, hi = origin + testing::kColumnTankMax;
  const bool expected[6] = {true, true, true, false, true, true};
  const float truth[6] = {lo.x(), hi.x(), lo.y(), 0.0f, lo.z(), hi.z()};
  for (int side = 0; side < 6; ++side) {
    EXPECT_EQ(c.wall[size_t(side)], expected[side]) << side << ": " << c.summary;
    if (expected[side]) {
      EXPECT_NEAR(c.plane[size_t(side)], truth[side], 0.1f * kSeqRadius) << side << ": " << c.summary;
    }
  }
  // The tank's walls are those planes; its open top is as high as the fluid went (20 cells), plus r.
  EXPECT_NEAR(c.tank->min.x(), lo.x(), 0.1f * kSeqRadius);
  EXPECT_NEAR(c.tank->max.x(), hi.x(), 0.1f * kSeqRadius);
  EXPECT_NEAR(c.tank->max.y(), lo.y() + 40.0f * kSeqRadius, 0.1f * kSeqRadius);
  EXPECT_TRUE(c.tank->open_top);
  EXPECT_TRUE(c.closed);
  // Why: the front arrived at +x in frame 8 (the 8th frame: 10 + 3 * 7 cells reach 30); the others held.
  EXPECT_NE(c.why[PlusX].find("reached in frame 8"), std::string::npos) << c.why[PlusX];
  EXPECT_NE(c.why[MinusX].find("from frame 1"), std::string::npos) << c.why[MinusX];
  EXPECT_NE(c.summary.find("container inferred from the fluid: walls -x at"), std::string::npos) << c.summary;
}

TEST(InferContainer, InventsNoWallAroundABlockFallingFreely) {
  const InferredContainer c = infer_container(survey_of(testing::falling_block()), kSeqRadius, kY);
  EXPECT_FALSE(c.tank) << c.summary;
  for (int side = 0; side < 6; ++side) EXPECT_FALSE(c.wall[size_t(side)]) << side << ": " << c.summary;
  // The log says why: the bottom moves; the flat sides are no evidence, since the block keeps its shape.
  EXPECT_EQ(c.summary.rfind("no container inferred: no floor (-y: moves", 0), 0u) << c.summary;
  for (Side side : {MinusX, PlusX, MinusZ, PlusZ})
    EXPECT_EQ(c.why[side].rfind("no evidence: flat at", 0), 0u) << side << ": " << c.why[side];
}

TEST(InferContainer, InventsNoWallAroundAFluidAtRest) {
  const std::vector<std::vector<Vec3f>> frames(12, testing::cells(Vec3f::Zero(), 10, 10, 10));
  const InferredContainer c = infer_container(survey_of(frames), kSeqRadius, kY);
  EXPECT_FALSE(c.tank) << c.summary;
  EXPECT_NE(c.why[MinusY].find("does not flow"), std::string::npos) << c.why[MinusY];
}

TEST(InferContainer, APuddleThatStoppedSpreadingHasNoWallAtItsRim) {
  // Spreading both ways along x (a cell a frame each side) and sinking for 8 frames, then at rest for 8.
  std::vector<std::vector<Vec3f>> frames;
  for (int k = 0; k < 16; ++k) {
    const int m = std::min(k, 7);
    frames.push_back(testing::cells(Vec3f(-0.02f * float(m), 0, 0), 10 + 2 * m, 20 - 2 * m, 5));
  }
  const InferredContainer c = infer_container(survey_of(frames), kSeqRadius, kY);
  ASSERT_TRUE(c.tank) << c.summary;  // it sits on the floor, and the z sides held while it spread
  for (Side side : {MinusX, PlusX}) {
    EXPECT_FALSE(c.wall[side]) << c.summary;
    EXPECT_NE(c.why[side].find("but the fluid does not flow while there"), std::string::npos) << c.why[side];
  }
}

TEST(InferContainer, AFluidThatChangesShapeInTheAirHasNoWalls) {
  // A block in free fall that also stretches along x (both x sides move) and keeps its z sides flat:
  // nothing holds it up, so its flat sides are no walls.
  std::vector<std::vector<Vec3f>> frames;
  for (int k = 0; k < 16; ++k) {
    const float t = float(k) / 25.0f;
    frames.push_back(testing::cells(Vec3f(-0.02f * float(k), 4.0f - 4.905f * t * t, 0.0f), 8 + 2 * k, 8, 8));
  }
  const InferredContainer c = infer_container(survey_of(frames), kSeqRadius, kY);
  EXPECT_FALSE(c.tank) << c.summary;
  EXPECT_FALSE(c.wall[MinusZ]) << c.summary;
  EXPECT_NE(c.why[MinusZ].find("nothing holds the fluid up"), std::string::npos) << c.why[MinusZ];
}

TEST(InferContainer, ASideReachedOnlyInTheLastFramesIsWeakEvidenceNotAWall) {
  // The column's front reaches its furthest cell in the last two frames only.
  std::vector<std::vector<Vec3f>> frames;
  for (int k = 0; k < 12; ++k) frames.push_back(testing::cells(Vec3f::Zero(), std::min(10 + 2 * k, 30), 20 - k, 5));
  const InferredContainer c = infer_container(survey_of(frames), kSeqRadius, kY);
  ASSERT_TRUE(c.tank) << c.summary;  // the floor, -x and the z sides held from the start
  EXPECT_FALSE(c.wall[PlusX]) << c.summary;
  EXPECT_EQ(c.why[PlusX].rfind("weak evidence: at x = ", 0), 0u) << c.why[PlusX];
  EXPECT_NE(c.summary.find("open: +x (weak evidence"), std::string::npos) << c.summary;
}

TEST(InferContainer, AMovingPistonIsLeftOpen) {
  const std::vector<std::vector<Vec3f>> frames = testing::column_at_a_piston();
  const InferredContainer c = infer_container(survey_of(frames), kSeqRadius, kY);
  ASSERT_TRUE(c.tank) << c.summary;
  EXPECT_FALSE(c.wall[MinusX]) << c.summary;
  EXPECT_TRUE(c.wall[PlusX]) << c.summary;  // the far wall: 0.08 + 26 cells = 0.6
  EXPECT_NEAR(c.plane[PlusX], 0.6f, 0.1f * kSeqRadius);
  EXPECT_EQ(c.why[MinusX].rfind("moves", 0), 0u) << c.why[MinusX];
  EXPECT_FALSE(c.closed);  // the tank's -x wall lies far away
  EXPECT_LT(c.tank->min.x(), -1.0f);
}

TEST(InferContainer, EmptyFramesChangeNothing) {
  // An emitter-like start: six empty frames (and one of 3 particles, no sheet) before the column.
  const Vec3f origin(5.0f, 2.0f, -3.0f);
  const std::vector<std::vector<Vec3f>> column = testing::collapsing_column(origin);
  std::vector<std::vector<Vec3f>> frames(6);
  frames.push_back({origin, origin + Vec3f(0.02f, 0, 0), origin + Vec3f(0.04f, 0, 0)});
  frames.insert(frames.end(), column.begin(), column.end());
  const InferredContainer with = infer_container(survey_of(frames), kSeqRadius, kY);
  const InferredContainer without = infer_container(survey_of(column), kSeqRadius, kY);
  ASSERT_TRUE(with.tank) << with.summary;
  for (size_t side = 0; side < 6; ++side) {
    EXPECT_EQ(with.wall[side], without.wall[side]) << side << ": " << with.summary;
    if (without.wall[side]) {
      EXPECT_EQ(with.plane[side], without.plane[side]) << side;
    }
    EXPECT_EQ(with.pressed_share[side], without.pressed_share[side]) << side;
  }
}

TEST(InferContainer, NoFrameWithASheetIsSaidSo) {
  const std::vector<std::vector<Vec3f>> frames(5);
  const InferredContainer c = infer_container(survey_of(frames), kSeqRadius, kY);
  EXPECT_FALSE(c.tank);
  EXPECT_NE(c.summary.find("no frame of the sequence holds 4 fluid particles"), std::string::npos) << c.summary;
}

}  // namespace
}  // namespace spume
