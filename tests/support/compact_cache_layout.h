#pragma once
// For tests that look inside a quantized compact diffuse cache (spume_cache.h): where each column
// starts, walked from the layout written down here independently of the reader.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace spume::testing {

constexpr size_t kCompactHeaderBytes = 136;
// The quantized columns in file order.
enum CompactColumn { kCells, kCellCounts, kOffsets, kVelocities, kLifetimes, kTypes, kIds, kColumns };

// Each column's start (its 16-byte prefix: raw bytes, stored bytes), in file order.
inline std::vector<size_t> column_starts(const std::string& file) {
  std::vector<size_t> at;
  size_t pos = kCompactHeaderBytes;
  for (int c = 0; c < kColumns; ++c) {
    at.push_back(pos);
    uint64_t stored = 0;
    std::memcpy(&stored, file.data() + pos + 8, 8);
    pos += 16 + stored;
  }
  EXPECT_EQ(pos, file.size() - 4);
  return at;
}

}  // namespace spume::testing
