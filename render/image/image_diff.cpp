#include "image_diff.h"

#include <algorithm>
#include <cstdlib>

#include "core/error.h"
#include "png_io.h"

namespace spume {
namespace {
void check_same_size(const ImageRGB8& a, const ImageRGB8& b) {
  if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size())
    fail("image comparison: sizes differ (", a.width, "x", a.height, " vs ", b.width, "x", b.height, ")");
}
}  // namespace

ImageDiff compare_images(const ImageRGB8& a, const ImageRGB8& b) {
  check_same_size(a, b);
  ImageDiff d;
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    int m = 0;
    for (size_t c = 0; c < 3; ++c) m = std::max(m, std::abs(int(a.rgb[3 * i + c]) - int(b.rgb[3 * i + c])));
    d.over_1 += m > 1;
    d.over_3 += m > 3;
    d.max_diff = std::max(d.max_diff, m);
  }
  return d;
}

bool within_regression_tolerance(const ImageDiff& diff, size_t pixel_count) {
  // 0.02% of the pixels, in integers: over_1 / pixel_count <= 2 / 10000.
  return diff.over_3 == 0 && diff.over_1 * 10000 <= 2 * pixel_count;
}

ImageRGB8 difference_image(const ImageRGB8& a, const ImageRGB8& b) {
  check_same_size(a, b);
  ImageRGB8 out(a.width, a.height);
  for (size_t i = 0; i < a.rgb.size(); ++i) out.rgb[i] = uint8_t(std::min(255, 16 * std::abs(int(a.rgb[i]) - int(b.rgb[i]))));
  return out;
}

void write_difference_png(const std::filesystem::path& path, const ImageRGB8& a, const ImageRGB8& b) {
  write_png(path, difference_image(a, b));
}

}  // namespace spume
