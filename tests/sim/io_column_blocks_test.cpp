// The Blosc block of a cache's columns (column_codec.h): the block asked for is the one each chunk
// records, either size reads back bit for bit, and a frame takes the large blocks from 2^21
// particles on.
#include <blosc.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "sim/io/column_codec.h"
#include "sim/io/spume_cache.h"
#include "tests/support/compact_cache_layout.h"
#include "tests/support/files.h"
#include "tests/support/spread_diffuse_frame.h"
#include "tests/support/temp_dir.h"

using namespace spume;
using namespace spume::testing;

namespace {

// The documented rule (sim/MODEL.md §11): 1 MiB chunks, each one block in frames of
// 2^21 particles or more, four of 256 KiB below.
constexpr size_t kChunk = size_t(1) << 20, kSmall = size_t(256) << 10, kLarge = kChunk;
constexpr size_t kThreshold = size_t(1) << 21;

// The block size each Blosc chunk of the column starting at `column` records, from Blosc's own header.
std::vector<size_t> chunk_blocks(const char* column) {
  uint64_t prefix[2];
  std::memcpy(prefix, column, 16);
  std::vector<size_t> blocks;
  for (size_t at = 0; at < prefix[1];) {
    size_t nbytes = 0, cbytes = 0, block = 0;
    blosc_cbuffer_sizes(column + 16 + at, &nbytes, &cbytes, &block);
    blocks.push_back(block);
    at += cbytes;
  }
  return blocks;
}

TEST(ColumnBlocks, EitherBlockReadsBackBitForBitAndIsTheOneEachChunkRecords) {
  // 3.5 MiB of smooth 16-bit values with noise: three full chunks and a half one.
  const size_t n = (7 * kChunk / 2) / 2;
  std::vector<int16_t> values(n);
  std::mt19937 rng(3);
  for (size_t i = 0; i < n; ++i) values[i] = int16_t(3000.0 * std::sin(double(i) * 1e-3) + double(rng() % 64));
  for (size_t block : {kSmall, kLarge}) {
    CacheBytes out;
    append_column(out, values.data(), n * 2, 2, true, block);
    EXPECT_EQ(chunk_blocks(out.data()),
              (std::vector<size_t>{block, block, block, std::min(block, kChunk / 2)}))
        << block;
    std::vector<int16_t> back(n);
    io::ByteReader r(out.view(), "column");
    read_column(r, back.data(), n * 2, "test");
    EXPECT_TRUE(back == values) << block;
  }
}

TEST(ColumnBlocks, FramesFromTwoMillionParticlesOnAreStoredInLargeBlocks) {
  TempDir dir;
  for (size_t n : {kThreshold - 1, kThreshold}) {
    const DiffuseFrame d = spread_diffuse_frame(n);
    const auto p = dir.path / "large.spd";
    write_diffuse_cache(p, d, 0.01 / 64);
    const std::string bytes = read_file(p);
    // The id column, 8 n bytes: 16 chunks, each but the last (which may be short) one or four blocks.
    const std::vector<size_t> blocks = chunk_blocks(bytes.data() + column_starts(bytes)[kIds]);
    const size_t want = n >= kThreshold ? kLarge : kSmall;
    ASSERT_EQ(blocks.size(), 16u);
    for (size_t c = 0; c + 1 < blocks.size(); ++c) EXPECT_EQ(blocks[c], want) << n << " particles, chunk " << c;
    // Every particle comes back (the bounds on its values: io_diffuse_quantized_test.cpp).
    std::vector<uint64_t> ids = read_diffuse_cache(p).ids, sent = d.ids;
    std::sort(ids.begin(), ids.end());
    std::sort(sent.begin(), sent.end());
    EXPECT_TRUE(ids == sent) << n;
  }
}

}  // namespace
