#pragma once
// What identifies an input file's content for deciding whether outputs made from it are current:
// its size and its modification time in nanoseconds, as make and ninja judge files. A re-export,
// a copy or an edit changes the time; reading every byte to hash it would cost as much as reading
// the frame, on every run, for caches of many gigabytes. Not caught: a rewrite that keeps both the
// size and the time (`cp -p`, `rsync -t` of different content); `--force` re-simulates.
#include <cstdint>
#include <filesystem>
#include <string>

namespace spume {

struct FileIdentity {
  uint64_t size = 0;
  int64_t mtime_ns = 0;
  bool operator==(const FileIdentity&) const = default;
  std::string text() const;  // "SIZE bytes, modified YYYY-MM-DD HH:MM:SS.nnnnnnnnn UTC"
};

// Throws Error naming the file when it cannot be read.
FileIdentity file_identity(const std::filesystem::path& path);

}  // namespace spume
