#include "render/image/difference_maps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>

#include "sim/core/error.h"
#include "render/image/thumbnail.h"

namespace spume {
namespace {

void check_same_size(const ImageRGB8& a, const ImageRGB8& b, const char* what) {
  if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size())
    fail(what, ": sizes differ (", a.width, "x", a.height, " vs ", b.width, "x", b.height, ")");
}

struct Stop {
  double t;
  Rgb8 colour;
};
// t = log2(1 + level) / 8 at levels 1, 3, 15, 63, 255.
constexpr std::array<Stop, 5> kRamp = {{{0.125, {40, 60, 200}},
                                        {0.25, {0, 150, 255}},
                                        {0.5, {60, 200, 60}},
                                        {0.75, {255, 200, 0}},
                                        {1.0, {255, 30, 30}}}};

std::array<Rgb8, 256> make_heat_table() {
  std::array<Rgb8, 256> table{};
  for (int level = 1; level < 256; ++level) {
    const double t = std::log2(1.0 + level) / 8.0;
    size_t k = 1;
    while (k + 1 < kRamp.size() && t > kRamp[k].t) ++k;
    const Stop &lo = kRamp[k - 1], &hi = kRamp[k];
    const double f = std::clamp((t - lo.t) / (hi.t - lo.t), 0.0, 1.0);
    auto mix = [f](uint8_t u, uint8_t v) { return uint8_t(std::lround(u + f * (double(v) - double(u)))); };
    table[size_t(level)] = {mix(lo.colour.r, hi.colour.r), mix(lo.colour.g, hi.colour.g), mix(lo.colour.b, hi.colour.b)};
  }
  return table;
}

}  // namespace

ImageRGB8 scaled_difference(const ImageRGB8& a, const ImageRGB8& b, int scale) {
  check_same_size(a, b, "difference image");
  if (scale < 1) fail("difference image: scale ", scale, " must be at least 1");
  ImageRGB8 out(a.width, a.height);
  for (size_t i = 0; i < a.rgb.size(); ++i)
    out.rgb[i] = uint8_t(std::min(255, scale * std::abs(int(a.rgb[i]) - int(b.rgb[i]))));
  return out;
}

Rgb8 heat_colour(int level) {
  static const std::array<Rgb8, 256> table = make_heat_table();
  return table[size_t(std::clamp(level, 0, 255))];
}

namespace {

// Each pixel's largest channel difference, as a grey image.
ImageRGB8 difference_levels(const ImageRGB8& a, const ImageRGB8& b) {
  ImageRGB8 out(a.width, a.height);
  for (size_t i = 0; i < a.pixel_count(); ++i) {
    int m = 0;
    for (size_t c = 0; c < 3; ++c) m = std::max(m, std::abs(int(a.rgb[3 * i + c]) - int(b.rgb[3 * i + c])));
    out.rgb[3 * i] = out.rgb[3 * i + 1] = out.rgb[3 * i + 2] = uint8_t(m);
  }
  return out;
}

// Heat colour where the level is non-zero, else the background pixel's integer Rec. 601 luma at 30%.
ImageRGB8 colour_levels(const ImageRGB8& levels, const ImageRGB8& background) {
  ImageRGB8 out(levels.width, levels.height);
  for (size_t i = 0; i < levels.pixel_count(); ++i) {
    const int m = levels.rgb[3 * i];
    const uint8_t* p = &background.rgb[3 * i];
    uint8_t* o = &out.rgb[3 * i];
    if (m == 0) {
      const int luma = (77 * p[0] + 150 * p[1] + 29 * p[2]) >> 8;
      o[0] = o[1] = o[2] = uint8_t(luma * 3 / 10);
    } else {
      const Rgb8 c = heat_colour(m);
      o[0] = c.r, o[1] = c.g, o[2] = c.b;
    }
  }
  return out;
}

}  // namespace

ImageRGB8 difference_heat_map(const ImageRGB8& a, const ImageRGB8& b) {
  check_same_size(a, b, "heat map");
  return colour_levels(difference_levels(a, b), a);
}

ImageRGB8 difference_heat_thumbnail(const ImageRGB8& a, const ImageRGB8& b, int max_width) {
  check_same_size(a, b, "heat map");
  return colour_levels(thumbnail_max(difference_levels(a, b), max_width), thumbnail(a, max_width));
}

}  // namespace spume
