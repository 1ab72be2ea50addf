#include "render/image/thumbnail.h"

#include <algorithm>

#include "sim/core/error.h"

namespace spume {
namespace {

enum class Reduce { mean, max };

ImageRGB8 shrink(const ImageRGB8& image, int max_width, Reduce reduce) {
  if (max_width < 1) fail("thumbnail: width ", max_width, " must be at least 1");
  if (image.width < 1 || image.height < 1 || image.rgb.size() != image.pixel_count() * 3)
    fail("thumbnail: empty or malformed image (", image.width, "x", image.height, ")");
  if (image.width <= max_width) return image;
  const auto [w, h] = thumbnail_size(image.width, image.height, max_width);
  ImageRGB8 out(w, h);
  for (int y = 0; y < h; ++y) {
    const int y0 = int(int64_t(y) * image.height / h), y1 = std::max(y0 + 1, int(int64_t(y + 1) * image.height / h));
    for (int x = 0; x < w; ++x) {
      const int x0 = int(int64_t(x) * image.width / w), x1 = std::max(x0 + 1, int(int64_t(x + 1) * image.width / w));
      uint64_t acc[3] = {0, 0, 0};
      for (int sy = y0; sy < y1; ++sy)
        for (int sx = x0; sx < x1; ++sx)
          for (int c = 0; c < 3; ++c)
            acc[c] = reduce == Reduce::mean ? acc[c] + image.at(sx, sy)[c] : std::max<uint64_t>(acc[c], image.at(sx, sy)[c]);
      const uint64_t n = uint64_t(y1 - y0) * uint64_t(x1 - x0);
      for (int c = 0; c < 3; ++c) out.at(x, y)[c] = uint8_t(reduce == Reduce::mean ? (acc[c] + n / 2) / n : acc[c]);
    }
  }
  return out;
}

}  // namespace

ThumbnailSize thumbnail_size(int width, int height, int max_width) {
  if (width <= max_width) return {width, height};
  return {max_width, std::max(1, int((int64_t(height) * max_width + width / 2) / width))};
}

ImageRGB8 thumbnail(const ImageRGB8& image, int max_width) { return shrink(image, max_width, Reduce::mean); }
ImageRGB8 thumbnail_max(const ImageRGB8& image, int max_width) { return shrink(image, max_width, Reduce::max); }

}  // namespace spume
