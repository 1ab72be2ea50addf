#pragma once
// Small copies of frames for reports that list hundreds of frames.
#include "render/image/image.h"

namespace spume {

// The image scaled down to at most `max_width` pixels wide (aspect kept, height at least 1), each
// output pixel the rounded mean of its box of source pixels (columns [x W / w, (x + 1) W / w), rows
// likewise), so every source pixel counts once. Images no wider than max_width are returned as
// they are. Throws Error for max_width < 1 or an empty image.
ImageRGB8 thumbnail(const ImageRGB8& image, int max_width);

// The size thumbnail() gives an image of width x height: {w, h}.
struct ThumbnailSize {
  int width, height;
};
ThumbnailSize thumbnail_size(int width, int height, int max_width);

// The same boxes, each output channel the largest of its box: a one-pixel mark survives shrinking.
ImageRGB8 thumbnail_max(const ImageRGB8& image, int max_width);

}  // namespace spume
