#pragma once
// Which files a run of spume wrote, seen on disk without waiting for the clock: mark_files gives
// every file in a folder a modification time long past (2001-09-09 01:46:40 UTC), which no file spume
// writes can carry; a file whose time is no longer the mark was written (or replaced) since.
// spume's own caches are identified by their CRC-32 (sim/io/file_identity.h), so marking them changes
// nothing spume decides; mark only folders of spume's outputs (caches, records, frames).
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

namespace spume::testing {

inline std::filesystem::file_time_type written_mark() {
  return std::chrono::file_clock::from_sys(std::chrono::sys_seconds(std::chrono::seconds(1000000000)));
}

// Marks every regular file directly in `folder`.
inline void mark_files(const std::filesystem::path& folder) {
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file()) std::filesystem::last_write_time(entry.path(), written_mark());
}

// The names of the regular files directly in `folder` written since mark_files (or new since), sorted.
inline std::vector<std::string> written_since_mark(const std::filesystem::path& folder) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(folder))
    if (entry.is_regular_file() && std::filesystem::last_write_time(entry.path()) != written_mark())
      names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace spume::testing
