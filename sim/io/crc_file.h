#pragma once
// The one way spume writes its binary files (fluid and diffuse caches, the solver's restart state):
// a header, whole arrays in one write each (large frames stream at disk speed), and the CRC-32 of
// every byte before it as a little-endian trailer, all through a temporary file renamed into place.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/core/atomic_file.h"
#include "sim/io/crc32.h"

namespace spume {

template <typename... Arrays>
void write_crc_file(const std::filesystem::path& path, const std::string& header, const Arrays&... arrays) {
  write_file_atomically(path, [&](std::ostream& out) {
    uint32_t crc = crc32_start();
    auto put = [&](const void* data, size_t bytes) {
      if (bytes == 0) return;
      out.write(static_cast<const char*>(data), std::streamsize(bytes));
      crc = crc32_update(crc, data, bytes);
    };
    put(header.data(), header.size());
    (put(arrays.data(), arrays.size() * sizeof(typename Arrays::value_type)), ...);
    out.write(reinterpret_cast<const char*>(&crc), 4);  // x86-64 and arm64 are little-endian
  });
}

}  // namespace spume
