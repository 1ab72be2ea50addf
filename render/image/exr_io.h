#pragma once
// OpenEXR files via Debian's OpenEXR library: scan lines, ZIP (lossless, in blocks of 16 rows), channels
// HALF or FLOAT. Writes are atomic (temporary file + rename); every error names the file.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace spume {

struct ExrChannel {
  std::string name;          // "R", "spray.A", "Z"
  const float* first;        // the top-left pixel's value
  size_t stride;             // floats from one pixel's value to the next; rows follow each other
  bool full_float = false;   // FLOAT in the file; otherwise HALF (rounded to nearest)
};

using ExrStrings = std::vector<std::pair<std::string, std::string>>;  // string attributes of the header

// width x height pixels, rows top to bottom. Throws Error naming `path`.
void write_exr(const std::filesystem::path& path, int width, int height, const std::vector<ExrChannel>& channels,
               const ExrStrings& strings);

// A string attribute of the file's header; nullopt for a missing or unreadable file or attribute.
std::optional<std::string> read_exr_string(const std::filesystem::path& path, const std::string& name);

// A whole file, every channel as float (for tests and `spume info`). Throws Error naming `path`.
struct ExrContents {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> channels;
  std::map<std::string, std::string> strings;
  std::map<std::string, bool> full_float;  // per channel: FLOAT in the file (else HALF)
  std::string compression;
};
ExrContents read_exr(const std::filesystem::path& path);

}  // namespace spume
