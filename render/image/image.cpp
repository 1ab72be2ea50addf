#include "render/image/image.h"

#include <algorithm>
#include <array>
#include <bit>
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

namespace {

// The code by the formula: one pow per call.
uint8_t srgb_encode8_by_formula(float linear) {
  if (!(linear > 0.0f)) return 0;  // also maps NaN to black rather than to an arbitrary code
  return uint8_t(std::lround(double(srgb_encode(linear)) * 255.0));
}

// The formula's codes without its pow. threshold[k], k = 1..255: the smallest float whose code by the
// formula is k or more, found by bisecting the positive floats' bit patterns (which order as their
// values do). The formula never decreases (a double pow, rounded to float, then scaled and rounded:
// checked over every float when this was written), so the code of x is the number of thresholds at
// or below x. To find it, the floats from 2^-14 up are cut into buckets of 2^16 consecutive bit
// patterns (1/128 of an octave); first[b] is the code where bucket b starts, and within a bucket the
// code rises by one at most (0.61 codes a bucket where the curve is steepest, at 1), so one more
// comparison settles it. Below 2^-14 every code is 0 (12.92 x 255 x 2^-14 = 0.2).
class SrgbEncoder {
 public:
  SrgbEncoder() {
    const uint32_t one = std::bit_cast<uint32_t>(1.0f);
    for (int k = 1; k < 256; ++k) {
      uint32_t lo = 0, hi = one;  // code(lo) < k <= code(hi): code(+0) = 0, code(1) = 255
      while (hi - lo > 1) {
        const uint32_t mid = lo + (hi - lo) / 2;
        (srgb_encode8_by_formula(std::bit_cast<float>(mid)) >= k ? hi : lo) = mid;
      }
      threshold_[size_t(k)] = std::bit_cast<float>(hi);
    }
    threshold_[0] = 0.0f, threshold_[256] = INFINITY;
    uint8_t code = 0;  // the buckets start in increasing order, so the count carries over
    for (size_t b = 0; b < kBuckets; ++b) {
      const float start = std::bit_cast<float>(kFirstBits + uint32_t(b << kBucketShift));
      while (code < 255 && start >= threshold_[code + 1u]) ++code;
      first_[b] = code;
    }
  }

  uint8_t operator()(float linear) const {
    if (!(linear >= kSmallest)) return 0;  // also NaN, as the formula gives it
    if (linear >= 1.0f) return 255;
    uint32_t code = first_[(std::bit_cast<uint32_t>(linear) - kFirstBits) >> kBucketShift];
    while (linear >= threshold_[code + 1]) ++code;
    return uint8_t(code);
  }

 private:
  static constexpr float kSmallest = 0x1p-14f;
  static constexpr uint32_t kFirstBits = std::bit_cast<uint32_t>(kSmallest);
  static constexpr int kBucketShift = 16;
  static constexpr size_t kBuckets = ((std::bit_cast<uint32_t>(1.0f) - kFirstBits) >> kBucketShift) + 1;
  std::array<float, 257> threshold_{};
  std::array<uint8_t, kBuckets> first_{};
};

const SrgbEncoder& srgb_encoder() {
  static const SrgbEncoder encoder;
  return encoder;
}

}  // namespace

uint8_t srgb_encode8(float linear) { return srgb_encoder()(linear); }

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
  const SrgbEncoder& encode = srgb_encoder();
  // Rows in parallel; each byte has one writer.
  parallel_for(size_t(linear.height), 8, [&](size_t y0, size_t y1) {
    for (size_t i = y0 * size_t(linear.width); i < y1 * size_t(linear.width); ++i)
      for (int c = 0; c < 3; ++c) out.rgb[3 * i + size_t(c)] = encode(linear.rgb[i][c]);
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
