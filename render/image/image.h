#pragma once
// Images as plain arrays, top row first (the Camera's pixel convention): 8-bit sRGB for files and
// linear float RGB for everything that blends light. Conversions use the exact IEC 61966-2-1 curve.
#include <cstdint>
#include <vector>

#include "sim/core/vec.h"

namespace spume {

// 8-bit sRGB-encoded RGB, 3 bytes per pixel, rows top to bottom.
struct ImageRGB8 {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;

  ImageRGB8() = default;
  ImageRGB8(int w, int h) : width(w), height(h), rgb(size_t(w) * size_t(h) * 3, 0) {}
  size_t pixel_count() const { return size_t(width) * size_t(height); }
  uint8_t* at(int x, int y) { return rgb.data() + (size_t(y) * size_t(width) + size_t(x)) * 3; }
  const uint8_t* at(int x, int y) const { return rgb.data() + (size_t(y) * size_t(width) + size_t(x)) * 3; }
};

// Linear (scene-referred) RGB, one Vec3f per pixel, rows top to bottom.
struct ImageRGBf {
  int width = 0, height = 0;
  std::vector<Vec3f> rgb;

  ImageRGBf() = default;
  ImageRGBf(int w, int h, const Vec3f& fill = Vec3f::Zero()) : width(w), height(h), rgb(size_t(w) * size_t(h), fill) {}
  size_t pixel_count() const { return size_t(width) * size_t(height); }
  Vec3f& at(int x, int y) { return rgb[size_t(y) * size_t(width) + size_t(x)]; }
  const Vec3f& at(int x, int y) const { return rgb[size_t(y) * size_t(width) + size_t(x)]; }
};

// The sRGB transfer functions on [0, 1] (values outside are clamped first).
float srgb_encode(float linear);
float srgb_decode(float encoded);
// Linear value -> nearest 8-bit code; 8-bit code -> linear value (table, exact to float rounding).
uint8_t srgb_encode8(float linear);
float srgb_decode8(uint8_t code);

ImageRGB8 to_srgb8(const ImageRGBf& linear);
ImageRGBf to_linear(const ImageRGB8& srgb);

}  // namespace spume
