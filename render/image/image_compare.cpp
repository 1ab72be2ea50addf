#include "render/image/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "sim/core/error.h"

namespace spume {
namespace {
uint64_t pow10(int digits) {
  uint64_t p = 1;
  for (int i = 0; i < digits; ++i) p *= 10;
  return p;
}
}  // namespace

double DecimalPercent::value() const { return double(units) / double(pow10(digits)); }

std::string DecimalPercent::text() const {
  const uint64_t scale = pow10(digits);
  std::string s = std::to_string(units / scale);
  if (digits == 0) return s;
  std::string frac = std::to_string(units % scale);
  frac.insert(0, size_t(digits) - frac.size(), '0');
  while (!frac.empty() && frac.back() == '0') frac.pop_back();
  return frac.empty() ? s : s + "." + frac;
}

bool DecimalPercent::exceeded_by(uint64_t count, uint64_t total) const {
  // count / total * 100 > units / 10^digits  <=>  count * 100 * 10^digits > units * total.
  // With total <= 2^32 (65535^2 pixels at most), digits <= 6 and units <= 10^8 both sides fit 64 bits.
  return count * 100 * pow10(digits) > units * total;
}

double PixelStats::over_fail_percent() const { return pixels ? 100.0 * double(over_fail) / double(pixels) : 0.0; }
double PixelStats::mean_diff() const { return pixels ? double(sum_abs) / double(3 * pixels) : 0.0; }
double PixelStats::rmse() const { return pixels ? std::sqrt(double(sum_sq) / double(3 * pixels)) : 0.0; }

double PixelStats::psnr_db() const {
  if (sum_sq == 0) return std::numeric_limits<double>::infinity();
  const double mse = double(sum_sq) / double(3 * pixels);
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

PixelStats compare_pixels(const ImageRGB8& a, const ImageRGB8& b, const CompareThresholds& t) {
  if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size())
    fail("image comparison: sizes differ (", a.width, "x", a.height, " vs ", b.width, "x", b.height, ")");
  PixelStats s;
  s.pixels = a.pixel_count();
  for (size_t i = 0; i < s.pixels; ++i) {
    int m = 0;
    for (size_t c = 0; c < 3; ++c) {
      const int d = std::abs(int(a.rgb[3 * i + c]) - int(b.rgb[3 * i + c]));
      m = std::max(m, d);
      s.sum_abs += uint64_t(d);
      s.sum_sq += uint64_t(d * d);
    }
    s.over_fail += m > t.fail;
    s.over_hardfail += m > t.hardfail;
    s.max_diff = std::max(s.max_diff, m);
  }
  return s;
}

ThresholdVerdict judge(const PixelStats& s, const CompareThresholds& t) {
  ThresholdVerdict v;
  v.over_failpercent = t.failpercent.exceeded_by(s.over_fail, s.pixels);
  v.over_hardfail = s.max_diff > t.hardfail;
  return v;
}

}  // namespace spume
