#pragma once
// What identifies an input file's content for deciding whether outputs made from it are current.
//  - spume's own caches (.spf, .spd) end with a CRC-32 of their content: their identity is the size
//    and that CRC, read from the last 4 bytes. Copying an output folder (which resets modification
//    times) keeps them current; any change of content changes the CRC.
//  - Any other file (another simulator's cache): its size and modification time in nanoseconds, as
//    make and ninja judge files. A re-export, a copy or an edit changes the time; hashing every byte
//    on every run would cost as much as reading the frames, for caches of many gigabytes. Not caught:
//    a rewrite that keeps both the size and the time (`cp -p`, `rsync -t` of other content of the same
//    size); `--force` re-simulates.
#include <cstdint>
#include <filesystem>
#include <string>

namespace spume {

struct FileIdentity {
  uint64_t size = 0;
  int64_t mtime_ns = 0;  // 0 for spume caches
  uint32_t crc = 0;      // spume caches: the CRC-32 trailer; 0 otherwise
  bool operator==(const FileIdentity&) const = default;
  std::string text() const;  // "N bytes, modified YYYY-MM-DD HH:MM:SS.nnnnnnnnn UTC" or "N bytes, CRC-32 xxxxxxxx"
};

// Throws Error naming the file when it cannot be read.
FileIdentity file_identity(const std::filesystem::path& path);

}  // namespace spume
