#pragma once
// Image regression on decoded 8-bit pixels, with the thresholds of OpenImageIO's idiff: a pixel's
// difference is its largest channel difference in 8-bit levels (1 level = 1/255 of full range); a
// pixel fails when that exceeds `fail`; a frame fails when more than `failpercent` percent of its
// pixels fail, or when any pixel exceeds `hardfail`. Sums are exact integers, so every figure is the
// same however the work is split.
#include <cstddef>
#include <cstdint>
#include <string>

#include "render/image/image.h"

namespace spume {

// A percentage held as an exact decimal, value = units / 10^digits, so that "0.02" compares with
// pixel counts exactly (a binary double would put the boundary a rounding error away from 2/10000).
struct DecimalPercent {
  static constexpr int kMaxDigits = 6;
  uint64_t units = 0;  // at most 100 * 10^digits
  int digits = 0;      // 0..kMaxDigits
  double value() const;
  std::string text() const;  // as a person writes it: "0.02", "5", "0"
  // True when count / total * 100 > value; exact (integers in 64 bits for totals up to 2^32 pixels).
  bool exceeded_by(uint64_t count, uint64_t total) const;
};

struct CompareThresholds {
  int fail = 1;                         // levels: a pixel fails when its difference exceeds this
  DecimalPercent failpercent{2, 2};     // 0.02 %: the share of failing pixels a frame may have
  int hardfail = 3;                     // levels: any pixel above fails the frame
};

// spume's own image-regression rule (tests/golden): at most 1/255 on all but 0.02% of the pixels and
// at most 3/255 anywhere. It absorbs compiler and libm drift; on one machine renders are
// byte-identical. These are also `spume compare`'s defaults.
inline CompareThresholds regression_thresholds() { return {}; }

struct PixelStats {
  size_t pixels = 0;
  size_t over_fail = 0;      // pixels whose difference exceeds thresholds.fail
  size_t over_hardfail = 0;  // pixels whose difference exceeds thresholds.hardfail
  int max_diff = 0;          // largest channel difference anywhere, levels
  uint64_t sum_abs = 0;      // sum of |a - b| over every channel of every pixel, levels
  uint64_t sum_sq = 0;       // sum of (a - b)^2 over every channel of every pixel, levels^2

  bool identical() const { return max_diff == 0; }
  double over_fail_percent() const;  // 100 * over_fail / pixels
  double mean_diff() const;          // mean |a - b| per channel value, levels
  double rmse() const;               // root mean square channel difference, levels
  // Peak signal-to-noise ratio 10 log10(255^2 / MSE) in dB, MSE over every channel value;
  // +infinity for identical images.
  double psnr_db() const;
};

// Throws Error when the sizes differ (callers that report a size mismatch check first).
PixelStats compare_pixels(const ImageRGB8& reference, const ImageRGB8& candidate, const CompareThresholds& thresholds);

struct ThresholdVerdict {
  bool over_failpercent = false;
  bool over_hardfail = false;
  bool pass() const { return !over_failpercent && !over_hardfail; }
};
ThresholdVerdict judge(const PixelStats& stats, const CompareThresholds& thresholds);

}  // namespace spume
