#pragma once
// Whole files as text, for tests that write inputs by hand or check what spume wrote.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace spume::testing {

// The file's bytes ("" when it cannot be opened).
inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// Writes `text` to `path`, making its parent folders.
inline void write_file(const std::filesystem::path& path, const std::string& text) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

}  // namespace spume::testing
