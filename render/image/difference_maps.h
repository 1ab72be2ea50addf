#pragma once
// Pictures of where two images differ: the absolute difference scaled up (idiff's -abs -scale), and
// a heat map of each pixel's largest channel difference over a dimmed grey copy of the reference.
#include <filesystem>

#include "render/image/bitmap_font.h"
#include "render/image/image.h"

namespace spume {

// |reference - candidate| per channel times `scale` (>= 1), clamped to 255. Throws Error when the
// sizes differ or the scale is below 1.
ImageRGB8 scaled_difference(const ImageRGB8& reference, const ImageRGB8& candidate, int scale);

// The heat map's colour for a pixel whose largest channel difference is `level` (1..255): a ramp in
// t = log2(1 + level) / 8, so 1, 3, 15, 63 and 255 levels sit at even steps (blue, light blue, green,
// amber, red) and a one-level change is as visible as a large one. Level 0 is not coloured.
Rgb8 heat_colour(int level);

// Pixels that differ get heat_colour(largest channel difference); pixels that do not show the
// reference's luma at 30% brightness, so the picture stays recognisable. Throws Error on sizes.
ImageRGB8 difference_heat_map(const ImageRGB8& reference, const ImageRGB8& candidate);

// The heat map at most `max_width` wide (thumbnail.h's boxes): each pixel coloured by the largest
// difference in its box, so a single changed pixel still shows; unchanged boxes show the dimmed
// luma of the reference's thumbnail.
ImageRGB8 difference_heat_thumbnail(const ImageRGB8& reference, const ImageRGB8& candidate, int max_width);

}  // namespace spume
