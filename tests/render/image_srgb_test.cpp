// sRGB transfer curve (IEC 61966-2-1) against values worked out by hand from the standard's formula.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "render/image/image.h"

namespace spume {
namespace {

TEST(ImageSrgb, EndpointsAndLinearSegment) {
  EXPECT_EQ(srgb_encode(0.0f), 0.0f);
  EXPECT_NEAR(srgb_encode(1.0f), 1.0f, 1e-7f);
  // Below the 0.0031308 threshold the curve is 12.92 x.
  EXPECT_NEAR(srgb_encode(0.001f), 0.01292f, 1e-8f);
  // At the threshold 12.92 * 0.0031308 = 0.040449936; the power branch meets it to ~3e-8 (the
  // standard's constants are rounded), and float(0.0031308) lies just above the threshold.
  EXPECT_NEAR(srgb_encode(0.0031308f), 0.040449936f, 1e-7f);
  EXPECT_NEAR(srgb_encode(0.0031309f), 0.0404512f, 2e-6f);  // power branch, continuous
  EXPECT_NEAR(srgb_decode(0.04045f), 0.0031308050f, 1e-9f);  // 0.04045 / 12.92
  // Out-of-range inputs are clamped.
  EXPECT_EQ(srgb_encode(-1.0f), 0.0f);
  EXPECT_NEAR(srgb_encode(4.0f), 1.0f, 1e-7f);
}

TEST(ImageSrgb, PowerSegmentKnownValues) {
  // 1.055 * 0.5^(1/2.4) - 0.055 = 1.055 * 0.749154 - 0.055 = 0.735357 -> 187.516 -> 188.
  EXPECT_NEAR(srgb_encode(0.5f), 0.7353570f, 1e-6f);
  EXPECT_EQ(srgb_encode8(0.5f), 188);
  // Mid grey 0.18: 1.055 * 0.18^(1/2.4) - 0.055 = 0.461356 -> 117.65 -> 118.
  EXPECT_NEAR(srgb_encode(0.18f), 0.4613561f, 1e-6f);
  EXPECT_EQ(srgb_encode8(0.18f), 118);
  // ((188/255 + 0.055) / 1.055)^2.4 = 0.750952^2.4 = 0.502886.
  EXPECT_NEAR(srgb_decode8(188), 0.5028865f, 1e-6f);
  // Encoded 0.5 is linear 0.214041 (the classic "50% grey is 21% light").
  EXPECT_NEAR(srgb_decode(0.5f), 0.2140411f, 1e-6f);
  EXPECT_EQ(srgb_encode8(0.0f), 0);
  EXPECT_EQ(srgb_encode8(1.0f), 255);
}

TEST(ImageSrgb, RoundTrips) {
  for (int code = 0; code < 256; ++code) EXPECT_EQ(srgb_encode8(srgb_decode8(uint8_t(code))), code) << code;
  for (float x = 0.0f; x <= 1.0f; x += 0.0137f) EXPECT_NEAR(srgb_decode(srgb_encode(x)), x, 1e-6f) << x;
}

// The 8-bit code as the standard defines it: the curve in double, rounded to float, times 255, rounded.
int code_by_formula(float linear) {
  if (!(linear > 0.0f)) return 0;
  const double x = std::min(double(linear), 1.0);
  const float e = float(x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
  return int(std::lround(double(e) * 255.0));
}

TEST(ImageSrgb, EightBitCodesAreTheFormulasAtEveryStepBetweenCodes) {
  // Where the formula steps from code k-1 to k (found here by bisection over the floats' bit
  // patterns), the floats just below and just above get the formula's codes; so do floats spread
  // over (0, 1.25] and the special values.
  const uint32_t one = std::bit_cast<uint32_t>(1.0f);
  for (int k = 1; k < 256; ++k) {
    uint32_t lo = 0, hi = one;
    while (hi - lo > 1) {
      const uint32_t mid = lo + (hi - lo) / 2;
      (code_by_formula(std::bit_cast<float>(mid)) >= k ? hi : lo) = mid;
    }
    for (uint32_t b = hi - 3; b <= hi + 3; ++b) {
      const float x = std::bit_cast<float>(b);
      ASSERT_EQ(srgb_encode8(x), code_by_formula(x)) << "code " << k << ", x = " << x;
    }
  }
  for (uint32_t b = 0; b <= std::bit_cast<uint32_t>(1.25f); b += 4099) {
    const float x = std::bit_cast<float>(b);
    ASSERT_EQ(srgb_encode8(x), code_by_formula(x)) << x;
  }
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (float x : {0.0f, -0.0f, -1.0f, -kInf, kInf, std::numeric_limits<float>::quiet_NaN(),
                  std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::max()})
    EXPECT_EQ(srgb_encode8(x), code_by_formula(x)) << x;
  EXPECT_EQ(srgb_encode8(kInf), 255);
  EXPECT_EQ(srgb_encode8(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(ImageSrgb, ImageConversion) {
  ImageRGBf lin(3, 2, Vec3f(0.5f, 0.18f, 0.0f));
  lin.at(2, 1) = Vec3f(1.0f, 2.0f, -1.0f);
  const ImageRGB8 enc = to_srgb8(lin);
  ASSERT_EQ(enc.rgb.size(), 18u);
  EXPECT_EQ(enc.at(0, 0)[0], 188);
  EXPECT_EQ(enc.at(0, 0)[1], 118);
  EXPECT_EQ(enc.at(0, 0)[2], 0);
  EXPECT_EQ(enc.at(2, 1)[0], 255);
  EXPECT_EQ(enc.at(2, 1)[1], 255);
  EXPECT_EQ(enc.at(2, 1)[2], 0);
  const ImageRGBf back = to_linear(enc);
  EXPECT_NEAR(back.at(1, 0).x(), 0.5028865f, 1e-6f);
}

}  // namespace
}  // namespace spume
