#pragma once
// Images and folders for the comparison tests: flat and random pictures, one-pixel edits, a fresh
// folder per test under out/tests/compare (kept after a failure, to be looked at).
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>

#include "render/image/image.h"
#include "tests/support/csv.h"
#include "tests/support/files.h"

namespace spume::testing {

inline ImageRGB8 flat_image(int w, int h, uint8_t value) {
  ImageRGB8 img(w, h);
  std::fill(img.rgb.begin(), img.rgb.end(), value);
  return img;
}

inline ImageRGB8 random_image(int w, int h, uint32_t seed) {
  ImageRGB8 img(w, h);
  std::mt19937 rng(seed);
  for (auto& v : img.rgb) v = uint8_t(rng() & 0xFF);
  return img;
}

// A copy with channel c of pixel (x, y) raised by `by` (the tests keep it within 0..255).
inline ImageRGB8 with_change(ImageRGB8 img, int x, int y, int c, int by) {
  img.at(x, y)[c] = uint8_t(img.at(x, y)[c] + by);
  return img;
}

// out/tests/compare/NAME, emptied: what a failing test left stays there to be looked at.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto dir = std::filesystem::path(SPUME_OUT_DIR) / "tests" / "compare" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace spume::testing
