#pragma once
// For tests that edit a spume cache on purpose: the CRC-32 trailer rewritten to match the edited
// bytes, so that the edit reaches the checks behind the CRC.
#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <string>

namespace spume::testing {

inline std::string with_fixed_crc(std::string bytes) {
  const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(bytes.data()), uInt(bytes.size() - 4)));
  std::memcpy(bytes.data() + bytes.size() - 4, &crc, 4);  // little-endian host, like the format
  return bytes;
}

}  // namespace spume::testing
