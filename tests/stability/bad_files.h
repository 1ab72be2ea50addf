#pragma once
// Particle files holding a non-finite value, which spume's writers refuse to produce: the frame is
// written with a marker value in its place, the marker's bytes are then replaced by the bad value's
// (gzip undone first, the cache's CRC-32 redone after), so every reader sees a well-formed file.
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "sim/core/error.h"

namespace spume::stability {

constexpr float kMarker = 1234.5f;

inline std::string file_bytes(const std::filesystem::path& path) {
  gzFile in = gzopen(path.c_str(), "rb");  // reads plain files as they are
  std::string bytes;
  char buffer[1 << 14];
  int n;
  while ((n = gzread(in, buffer, sizeof buffer)) > 0) bytes.append(buffer, size_t(n));
  gzclose(in);
  return bytes;
}

inline std::string float_bytes(float v, bool big_endian) {
  std::string b(4, '\0');
  std::memcpy(b.data(), &v, 4);
  if (big_endian) std::reverse(b.begin(), b.end());
  return b;
}

// Rewrites `path` (written with kMarker at the one place to spoil) with `bad` there instead.
inline void spoil_marker(const std::filesystem::path& path, float bad, bool big_endian, bool crc_trailer) {
  std::string bytes = file_bytes(path);
  const std::string marker = float_bytes(kMarker, big_endian);
  const size_t at = bytes.find(marker);
  if (at == std::string::npos || bytes.find(marker, at + 1) != std::string::npos)
    fail(path.string(), ": the marker value must occur exactly once");
  bytes.replace(at, 4, float_bytes(bad, big_endian));
  if (crc_trailer) {
    const uint32_t crc = uint32_t(crc32(0L, reinterpret_cast<const Bytef*>(bytes.data()), uInt(bytes.size() - 4)));
    std::memcpy(bytes.data() + bytes.size() - 4, &crc, 4);  // little-endian, as the cache
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace spume::stability
