// The Blosc block of a cache's columns (column_codec.h): the block asked for is the one each chunk
// records, either size reads back bit for bit, and a frame takes the large blocks from
// kLargeBlockParticles particles on.
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
#include "tests/support/temp_dir.h"

using namespace spume;
using namespace spume::testing;

namespace {

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
  const size_t n = (7 * kColumnChunkBytes / 2) / 2;
  std::vector<int16_t> values(n);
  std::mt19937 rng(3);
  for (size_t i = 0; i < n; ++i) values[i] = int16_t(3000.0 * std::sin(double(i) * 1e-3) + double(rng() % 64));
  for (size_t block : {kSmallColumnBlockBytes, kLargeColumnBlockBytes}) {
    CacheBytes out;
    append_column(out, values.data(), n * 2, 2, true, block);
    EXPECT_EQ(chunk_blocks(out.data()),
              (std::vector<size_t>{block, block, block, std::min(block, kColumnChunkBytes / 2)}))
        << block;
    std::vector<int16_t> back(n);
    io::ByteReader r(out.view(), "column");
    read_column(r, back.data(), n * 2, "test");
    EXPECT_TRUE(back == values) << block;
  }
}

DiffuseFrame spread_frame(size_t n) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  DiffuseFrame d;
  d.resize(n);
  for (size_t i = 0; i < n; ++i) {
    d.ids[i] = diffuse_id(uint32_t(i), 7, 0);
    d.positions[i] = Vec3f(3 * u(rng), 0.5f * u(rng), 2 * u(rng));
    d.velocities[i] = Vec3f(u(rng), -u(rng), 0.2f * u(rng));
    d.lifetimes[i] = 2 * u(rng);
    d.types[i] = DiffuseType(i % 3);
  }
  return d;
}

TEST(ColumnBlocks, FramesFromTwoMillionParticlesOnAreStoredInLargeBlocks) {
  TempDir dir;
  for (size_t n : {kLargeBlockParticles - 1, kLargeBlockParticles}) {
    const DiffuseFrame d = spread_frame(n);
    const auto p = dir.path / "large.spd";
    write_diffuse_cache(p, d, 0.01 / 64);
    const std::string bytes = read_file(p);
    // The id column, 8 n bytes: 16 chunks, each but the last (which may be short) one or four blocks.
    const std::vector<size_t> blocks = chunk_blocks(bytes.data() + column_starts(bytes)[kIds]);
    const size_t want = n >= kLargeBlockParticles ? kLargeColumnBlockBytes : kSmallColumnBlockBytes;
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
