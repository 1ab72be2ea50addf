// Pixel figures and thresholds of the comparison, on hand-worked one-pixel changes of a flat
// 100x100 grey image (10000 pixels, so one pixel is 0.01%), each just at and just past its limit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/compare/compare_test_support.h"
#include "sim/core/error.h"
#include "render/image/difference_maps.h"
#include "render/image/image_compare.h"
#include "render/image/thumbnail.h"

namespace spume {
namespace {

using testing::flat_image;
using testing::with_change;

const ImageRGB8 kGrey = flat_image(100, 100, 100);

TEST(ImageCompare, RegressionRuleIsTheGoldenTestsRule) {
  // tests/golden: at most 1/255 on all but 0.02% of the pixels, at most 3/255 anywhere.
  const CompareThresholds t = regression_thresholds();
  EXPECT_EQ(t.fail, 1);
  EXPECT_EQ(t.failpercent.text(), "0.02");
  EXPECT_EQ(t.hardfail, 3);
}

TEST(ImageCompare, IdenticalImagesHaveZeroErrorAndInfinitePsnr) {
  const ImageRGB8 img = testing::random_image(37, 23, 5);
  const PixelStats s = compare_pixels(img, img, regression_thresholds());
  EXPECT_EQ(s.pixels, 37u * 23u);
  EXPECT_EQ(s.over_fail, 0u);
  EXPECT_EQ(s.over_hardfail, 0u);
  EXPECT_EQ(s.max_diff, 0);
  EXPECT_EQ(s.mean_diff(), 0.0);
  EXPECT_EQ(s.rmse(), 0.0);
  EXPECT_TRUE(s.identical());
  EXPECT_EQ(s.psnr_db(), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(judge(s, regression_thresholds()).pass());
}

TEST(ImageCompare, FailLevelJustAtAndJustOver) {
  CompareThresholds t;  // fail 1
  t.failpercent = {0, 0};  // any failing pixel fails the frame
  const PixelStats at = compare_pixels(kGrey, with_change(kGrey, 5, 5, 1, 1), t);
  EXPECT_EQ(at.over_fail, 0u);  // 1 is not more than 1
  EXPECT_EQ(at.max_diff, 1);
  EXPECT_TRUE(judge(at, t).pass());
  const PixelStats over = compare_pixels(kGrey, with_change(kGrey, 5, 5, 1, 2), t);
  EXPECT_EQ(over.over_fail, 1u);
  EXPECT_DOUBLE_EQ(over.over_fail_percent(), 0.01);
  EXPECT_TRUE(judge(over, t).over_failpercent);
  EXPECT_FALSE(judge(over, t).over_hardfail);
}

TEST(ImageCompare, FailPercentJustAtAndJustOver) {
  const CompareThresholds t = regression_thresholds();
  ImageRGB8 two = with_change(with_change(kGrey, 1, 1, 0, 2), 2, 2, 2, 2);
  const PixelStats at = compare_pixels(kGrey, two, t);
  EXPECT_EQ(at.over_fail, 2u);  // 2 of 10000 = 0.02%: allowed
  EXPECT_TRUE(judge(at, t).pass());
  const PixelStats over = compare_pixels(kGrey, with_change(two, 3, 3, 1, 2), t);
  EXPECT_EQ(over.over_fail, 3u);  // 0.03%
  EXPECT_TRUE(judge(over, t).over_failpercent);
  EXPECT_FALSE(judge(over, t).over_hardfail);
}

TEST(ImageCompare, HardFailJustAtAndJustOver) {
  const CompareThresholds t = regression_thresholds();
  const PixelStats at = compare_pixels(kGrey, with_change(kGrey, 9, 0, 0, 3), t);
  EXPECT_EQ(at.max_diff, 3);
  EXPECT_EQ(at.over_hardfail, 0u);
  EXPECT_TRUE(judge(at, t).pass());  // one pixel over 1/255 is 0.01%, and 3 is not over 3
  const PixelStats over = compare_pixels(kGrey, with_change(kGrey, 9, 0, 0, 4), t);
  EXPECT_EQ(over.max_diff, 4);
  EXPECT_EQ(over.over_hardfail, 1u);
  EXPECT_FALSE(judge(over, t).over_failpercent);
  EXPECT_TRUE(judge(over, t).over_hardfail);
  // A pixel's difference is its largest channel: 4 in blue counts though red and green are equal.
  const PixelStats blue = compare_pixels(kGrey, with_change(kGrey, 0, 9, 2, 4), t);
  EXPECT_EQ(blue.max_diff, 4);
}

TEST(ImageCompare, MeanRmseAndPsnrByHand) {
  // One channel of one pixel off by 2: 30000 channel values, sum |d| = 2, sum d^2 = 4.
  const PixelStats one = compare_pixels(kGrey, with_change(kGrey, 5, 5, 1, 2), regression_thresholds());
  EXPECT_DOUBLE_EQ(one.mean_diff(), 2.0 / 30000.0);
  EXPECT_DOUBLE_EQ(one.rmse(), std::sqrt(4.0 / 30000.0));
  // 10 log10(255^2 * 30000 / 4) = 10 log10(487687500)
  EXPECT_NEAR(one.psnr_db(), 86.88141624259612, 1e-10);
  // Three channels of one pixel off by 2, 3 and 4: sum d^2 = 29.
  ImageRGB8 three = with_change(with_change(with_change(kGrey, 7, 7, 0, 2), 7, 7, 1, 3), 7, 7, 2, 4);
  const PixelStats s = compare_pixels(kGrey, three, regression_thresholds());
  EXPECT_EQ(s.over_fail, 1u);
  EXPECT_EQ(s.max_diff, 4);
  EXPECT_DOUBLE_EQ(s.mean_diff(), 9.0 / 30000.0);
  EXPECT_NEAR(s.psnr_db(), 78.27803617688618, 1e-10);
}

TEST(ImageCompare, SizesMustMatch) {
  EXPECT_THROW(compare_pixels(kGrey, flat_image(100, 99, 100), regression_thresholds()), Error);
}

TEST(DecimalPercent, ExactAtTheBoundary) {
  const DecimalPercent p{2, 2};  // 0.02
  EXPECT_FALSE(p.exceeded_by(2, 10000));
  EXPECT_TRUE(p.exceeded_by(3, 10000));
  // 960x540 = 518400 pixels: 0.02% is 103.68 pixels, so 103 pass and 104 fail.
  EXPECT_FALSE(p.exceeded_by(103, 518400));
  EXPECT_TRUE(p.exceeded_by(104, 518400));
  // The largest image and count in 64 bits.
  const uint64_t most = 65535ull * 65535ull;
  EXPECT_TRUE((DecimalPercent{99999999, 6}).exceeded_by(most, most));     // 100% > 99.999999%
  EXPECT_FALSE((DecimalPercent{100000000, 6}).exceeded_by(most, most));  // 100% is not > 100%
  EXPECT_EQ((DecimalPercent{0, 0}).text(), "0");
  EXPECT_EQ((DecimalPercent{5, 0}).text(), "5");
  EXPECT_EQ((DecimalPercent{1050, 3}).text(), "1.05");
  EXPECT_EQ((DecimalPercent{7, 6}).text(), "0.000007");
  EXPECT_DOUBLE_EQ((DecimalPercent{1050, 3}).value(), 1.05);
}

TEST(DifferenceMaps, ScaledDifferenceAndHeatMap) {
  const ImageRGB8 b = with_change(kGrey, 0, 0, 0, 4);
  const ImageRGB8 d = scaled_difference(kGrey, b, 16);
  EXPECT_EQ(d.at(0, 0)[0], 64);
  EXPECT_EQ(d.at(0, 0)[1], 0);
  EXPECT_EQ(d.at(1, 0)[0], 0);
  EXPECT_EQ(scaled_difference(kGrey, with_change(kGrey, 0, 0, 0, 100), 16).at(0, 0)[0], 255);  // clamped
  EXPECT_EQ(scaled_difference(kGrey, b, 1).at(0, 0)[0], 4);
  EXPECT_THROW(scaled_difference(kGrey, b, 0), Error);
  EXPECT_THROW(scaled_difference(kGrey, flat_image(3, 3, 0), 16), Error);

  // The ramp's stops sit at 1, 3, 15, 63 and 255 levels (t = log2(1 + level) / 8 = 1/8, 2/8, 4/8, 6/8, 1).
  EXPECT_EQ(heat_colour(1).b, 200);
  EXPECT_EQ(heat_colour(3).g, 150);
  EXPECT_EQ(heat_colour(15).r, 60);
  EXPECT_EQ(heat_colour(63).r, 255);
  EXPECT_EQ(heat_colour(63).g, 200);
  EXPECT_EQ(heat_colour(255).g, 30);
  const ImageRGB8 heat = difference_heat_map(kGrey, b);
  const Rgb8 four = heat_colour(4);
  EXPECT_EQ(heat.at(0, 0)[0], four.r);
  EXPECT_EQ(heat.at(0, 0)[1], four.g);
  EXPECT_EQ(heat.at(0, 0)[2], four.b);
  // Unchanged: grey 100 has integer luma (77 + 150 + 29) * 100 >> 8 = 100, at 30%: 30.
  EXPECT_EQ(heat.at(1, 0)[0], 30);
  EXPECT_EQ(heat.at(1, 0)[2], 30);
  // A thumbnail keeps a single changed pixel visible: the box's largest difference colours it.
  const ImageRGB8 small = difference_heat_thumbnail(kGrey, b, 10);
  EXPECT_EQ(small.width, 10);
  EXPECT_EQ(small.height, 10);
  EXPECT_EQ(small.at(0, 0)[0], four.r);
  EXPECT_EQ(small.at(1, 0)[0], 30);
}

TEST(Thumbnail, BoxMeansAndSizes) {
  ImageRGB8 img(4, 2);
  // Left 2x2 box: 0, 10, 20, 30 -> mean 15; right box: 255 everywhere.
  const uint8_t left[4] = {0, 10, 20, 30};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y)[c] = x < 2 ? left[y * 2 + x] : 255;
  const ImageRGB8 t = thumbnail(img, 2);
  ASSERT_EQ(t.width, 2);
  ASSERT_EQ(t.height, 1);
  EXPECT_EQ(t.at(0, 0)[0], 15);
  EXPECT_EQ(t.at(1, 0)[2], 255);
  EXPECT_EQ(thumbnail_max(img, 2).at(0, 0)[1], 30);
  EXPECT_EQ(thumbnail(img, 8).width, 4);  // never enlarged
  EXPECT_EQ(thumbnail_size(960, 540, 240).height, 135);
  EXPECT_EQ(thumbnail_size(1000, 1, 10).height, 1);
  EXPECT_THROW(thumbnail(img, 0), Error);
}

}  // namespace
}  // namespace spume
