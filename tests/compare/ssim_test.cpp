// SSIM against closed forms worked from the definition in Wang et al. (2004), not from the
// implementation's separable filtering: identical images, a constant offset (all variances zero),
// and one changed pixel in a flat image, where each window's statistics follow from the single
// Gaussian weight that falls on the pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tests/compare/compare_test_support.h"
#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "render/image/ssim.h"

namespace spume {
namespace {

using testing::flat_image;

const double C1 = (0.01 * 255) * (0.01 * 255), C2 = (0.03 * 255) * (0.03 * 255);

TEST(Ssim, IdenticalImagesGiveExactlyOne) {
  const ImageRGB8 img = testing::random_image(40, 30, 11);
  const SsimResult r = ssim_rgb(img, img);
  ASSERT_TRUE(r.defined);
  EXPECT_EQ(r.mean, 1.0);
  for (double c : r.channel) EXPECT_EQ(c, 1.0);
  // The shortcut the command takes for identical frames gives the same.
  const SsimResult quick = ssim_of_identical(40, 30);
  EXPECT_TRUE(quick.defined);
  EXPECT_EQ(quick.mean, r.mean);
  EXPECT_EQ(quick.channel, r.channel);
  EXPECT_FALSE(ssim_of_identical(10, 30).defined);
}

TEST(Ssim, ConstantOffsetIsTheLuminanceTermAlone) {
  // Flat 100 against flat 110: every window has mu_x = 100, mu_y = 110 and no variance, so
  // SSIM = (2 * 100 * 110 + C1) / (100^2 + 110^2 + C1) * (C2 / C2).
  const SsimResult r = ssim_rgb(flat_image(30, 20, 100), flat_image(30, 20, 110));
  ASSERT_TRUE(r.defined);
  EXPECT_NEAR(r.mean, (22000 + C1) / (22100 + C1), 1e-12);
  EXPECT_NEAR(r.mean, 0.9954764440915066, 1e-12);
}

TEST(Ssim, OnePixelInAFlatImageFromTheWindowWeights) {
  // 21x21 flat at v = 100, the centre pixel's red raised by d = 50. The 11x11 window positions
  // wholly inside are 11x11, and the centre pixel falls once under every weight w of the window.
  // There mu_x = v, mu_y = v + w d, sigma_x = 0, sigma_y^2 = w (1 - w) d^2, sigma_xy = 0.
  const double v = 100, d = 50;
  const ImageRGB8 a = flat_image(21, 21, 100);
  const ImageRGB8 b = testing::with_change(a, 10, 10, 0, 50);
  double weights[11][11], total = 0;
  for (int i = 0; i < 11; ++i)
    for (int j = 0; j < 11; ++j) total += weights[i][j] = std::exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / (2 * 1.5 * 1.5));
  double sum = 0;
  for (int i = 0; i < 11; ++i)
    for (int j = 0; j < 11; ++j) {
      const double w = weights[i][j] / total, my = v + w * d;
      sum += (2 * v * my + C1) / (v * v + my * my + C1) * C2 / (w * (1 - w) * d * d + C2);
    }
  const double red = sum / 121;
  const SsimResult r = ssim_rgb(a, b);
  ASSERT_TRUE(r.defined);
  EXPECT_NEAR(r.channel[0], red, 1e-12);
  EXPECT_EQ(r.channel[1], 1.0);
  EXPECT_EQ(r.channel[2], 1.0);
  EXPECT_NEAR(r.mean, (red + 2.0) / 3.0, 1e-12);
  EXPECT_LT(red, 0.99);  // clearly below 1: the window centred on the pixel gives it weight 0.07
}

// The definition evaluated directly: the 2-D window summed at every position, no separable
// passes, no bands, variances from centred sums.
double direct_ssim(const ImageRGB8& a, const ImageRGB8& b, int c) {
  double w[11][11], total = 0;
  for (int i = 0; i < 11; ++i)
    for (int j = 0; j < 11; ++j) total += w[i][j] = std::exp(-((i - 5) * (i - 5) + (j - 5) * (j - 5)) / 4.5);
  double sum = 0;
  for (int y0 = 0; y0 + 11 <= a.height; ++y0)
    for (int x0 = 0; x0 + 11 <= a.width; ++x0) {
      double mx = 0, my = 0;
      for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
          mx += w[i][j] / total * a.at(x0 + j, y0 + i)[c];
          my += w[i][j] / total * b.at(x0 + j, y0 + i)[c];
        }
      double vx = 0, vy = 0, cxy = 0;
      for (int i = 0; i < 11; ++i)
        for (int j = 0; j < 11; ++j) {
          const double dx = a.at(x0 + j, y0 + i)[c] - mx, dy = b.at(x0 + j, y0 + i)[c] - my;
          vx += w[i][j] / total * dx * dx, vy += w[i][j] / total * dy * dy, cxy += w[i][j] / total * dx * dy;
        }
      sum += (2 * mx * my + C1) * (2 * cxy + C2) / ((mx * mx + my * my + C1) * (vx + vy + C2));
    }
  return sum / ((a.width - 10) * (a.height - 10));
}

TEST(Ssim, MatchesTheDefinitionEvaluatedDirectly) {
  // 90 rows: output rows cross the 32-row bands the implementation works in.
  const ImageRGB8 a = testing::random_image(37, 90, 21);
  ImageRGB8 b = a;
  for (size_t i = 0; i < b.rgb.size(); i += 5) b.rgb[i] = uint8_t(std::min(255, b.rgb[i] + int(i % 40)));
  const SsimResult r = ssim_rgb(a, b);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(r.channel[size_t(c)], direct_ssim(a, b, c), 1e-12) << "channel " << c;
  EXPECT_LT(r.mean, 0.999);  // the edit is seen
}

TEST(Ssim, UndefinedBelowTheWindowAndSizesMustMatch) {
  EXPECT_FALSE(ssim_rgb(flat_image(10, 40, 0), flat_image(10, 40, 0)).defined);
  EXPECT_FALSE(ssim_rgb(flat_image(40, 10, 0), flat_image(40, 10, 0)).defined);
  EXPECT_TRUE(ssim_rgb(flat_image(11, 11, 0), flat_image(11, 11, 0)).defined);
  EXPECT_THROW(ssim_rgb(flat_image(20, 20, 0), flat_image(20, 21, 0)), Error);
}

TEST(Ssim, SameBitsForAnyThreadCount) {
  const ImageRGB8 a = testing::random_image(301, 157, 1), b = testing::random_image(301, 157, 2);
  set_thread_count(1);
  const SsimResult one = ssim_rgb(a, b);
  set_thread_count(2);
  const SsimResult two = ssim_rgb(a, b);
  set_thread_count(0);
  EXPECT_EQ(one.mean, two.mean);
  for (size_t c = 0; c < 3; ++c) EXPECT_EQ(one.channel[c], two.channel[c]);
  EXPECT_LT(one.mean, 0.1);  // unrelated noise is structurally dissimilar
}

}  // namespace
}  // namespace spume
