#include "sim/io/crc32.h"

#include <algorithm>
#include <vector>

#include <libdeflate.h>
#include <zlib.h>

#include "sim/core/parallel.h"

namespace spume {

uint32_t crc32_update(uint32_t crc, const void* data, size_t bytes) { return libdeflate_crc32(crc, data, bytes); }

uint32_t parallel_crc32(const void* data, size_t bytes) {
  constexpr size_t kPiece = size_t(4) << 20;
  const size_t pieces = (bytes + kPiece - 1) / kPiece;
  std::vector<uint32_t> crc(pieces);
  const char* p = static_cast<const char*>(data);
  parallel_for(pieces, 1, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c) crc[c] = crc32_update(0, p + c * kPiece, std::min(kPiece, bytes - c * kPiece));
  });
  uLong all = crc32_start();
  for (size_t c = 0; c < pieces; ++c) all = crc32_combine(all, crc[c], z_off_t(std::min(kPiece, bytes - c * kPiece)));
  return uint32_t(all);
}

}  // namespace spume
