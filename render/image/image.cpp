#include "render/image/image.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "sim/core/parallel.h"

namespace spume {

// IEC 61966-2-1: linear segment below 0.0031308 (encoded 0.04045), power 1/2.4 above. Evaluated in
// double so the float result is the correctly rounded curve, not a float pow's approximation.
float srgb_encode(float linear) {
  const double x = std::clamp(double(linear), 0.0, 1.0);
  return float(x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055);
}

float srgb_decode(float encoded) {
  const double s = std::clamp(double(encoded), 0.0, 1.0);
  return float(s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4));
}

uint8_t srgb_encode8(float linear) {
  if (!(linear > 0.0f)) return 0;  // also maps NaN to black rather than to an arbitrary code
  return uint8_t(std::lround(double(srgb_encode(linear)) * 255.0));
}

float srgb_decode8(uint8_t code) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgb_decode(float(i) / 255.0f);
    return t;
  }();
  return table[code];
}

ImageRGB8 to_srgb8(const ImageRGBf& linear) {
  ImageRGB8 out(linear.width, linear.height);
  // Rows in parallel: pow per channel is the cost (~6M calls at 1080p); each byte has one writer.
  parallel_for(size_t(linear.height), 8, [&](size_t y0, size_t y1) {
    for (size_t i = y0 * size_t(linear.width); i < y1 * size_t(linear.width); ++i)
      for (int c = 0; c < 3; ++c) out.rgb[3 * i + size_t(c)] = srgb_encode8(linear.rgb[i][c]);
  });
  return out;
}

ImageRGBf to_linear(const ImageRGB8& srgb) {
  ImageRGBf out(srgb.width, srgb.height);
  for (size_t i = 0; i < out.pixel_count(); ++i)
    out.rgb[i] = Vec3f(srgb_decode8(srgb.rgb[3 * i]), srgb_decode8(srgb.rgb[3 * i + 1]), srgb_decode8(srgb.rgb[3 * i + 2]));
  return out;
}

}  // namespace spume
