// The stretches of a ray in water from its surface crossings, cases worked by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "render/volume/water_path.h"

namespace spume {
namespace {

std::vector<WaterSegment> segments(std::vector<WaterCrossing> crossings, double origin_t = 0.0) {
  std::vector<WaterSegment> out;
  water_segments(crossings, origin_t, out);
  return out;
}

void expect_segments(const std::vector<WaterSegment>& got, const std::vector<WaterSegment>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].t0, want[i].t0) << i;
    EXPECT_EQ(got[i].t1, want[i].t1) << i;
  }
}

TEST(WaterPath, InAndOutInAnyOrder) {
  expect_segments(segments({{2.0, false}, {1.0, true}, {5.0, true}}), {{1.0, 2.0}, {5.0, INFINITY}});
}

TEST(WaterPath, ACameraUnderWaterStartsInWater) {
  expect_segments(segments({{3.0, false}}, -0.5), {{-0.5, 3.0}});
}

TEST(WaterPath, ACrossingReportedTwiceCountsOnce) {
  // A ray through an edge shared by two triangles: both report it, at the same t or an ulp apart.
  expect_segments(segments({{1.0, true}, {1.0, true}, {2.0, false}, {2.0 + 1e-12, false}}), {{1.0, 2.0}});
}

TEST(WaterPath, ASliverWhoseEntryAndExitSwappedIsDropped) {
  // Seen at the lighthouse (frame 149): a ray grazing a fold of the surface crosses a sliver of water
  // 6 um thick, and the float hits put its exit 2 um before its entry. Taken in that order, the exit
  // first said the camera was under water, and the 4.2 m before it dimmed a spray pixel. The sliver is
  // no crossing at all; the water the ray meets later is.
  expect_segments(segments({{4.2182608, false}, {4.2182631, true}, {4.7184634, true}}), {{4.7184634, INFINITY}});
  expect_segments(segments({{4.2182550, true}, {4.2182608, false}, {4.7184634, true}}), {{4.7184634, INFINITY}});
}

TEST(WaterPath, CrossingsFartherApartThanTheRoundingStaySeparate) {
  // 1 mm of water at 4 m: 25 times the merge distance.
  expect_segments(segments({{4.000, true}, {4.001, false}}), {{4.000, 4.001}});
  // The merge distance grows with the distance from the ray origin, not with t's reference.
  expect_segments(segments({{0.000, true}, {0.001, false}}, -4.0), {{0.000, 0.001}});
  expect_segments(segments({{4.0, true}, {4.0 + 0.5 * kMergeRelative * 4.0, false}}), {});
}

}  // namespace
}  // namespace spume
