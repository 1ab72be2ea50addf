#pragma once
// Images and folders for the comparison tests: flat and random pictures, one-pixel edits, a fresh
// temporary folder per test, and a small CSV reader for summary.csv.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "render/image/image.h"

namespace spume::test {

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

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Rows of cells; quoted cells ("a,b" and "" for a quote) as RFC 4180 writes them.
inline std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path) {
  std::vector<std::vector<std::string>> rows;
  const std::string text = read_text(path);
  std::vector<std::string> row;
  std::string cell;
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') cell += '"', ++i;
      else if (c == '"') quoted = false;
      else cell += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(cell), cell.clear();
    } else if (c == '\n') {
      row.push_back(cell), cell.clear();
      rows.push_back(row), row.clear();
    } else {
      cell += c;
    }
  }
  return rows;
}

}  // namespace spume::test
