// The pool behind HugeBuffer (io/huge_buffer.h): a freed block is taken again by a request it fits,
// and a request no kept block fits grows the largest kept block of at least half its size, keeping
// its pages (so only the growth is fresh memory), instead of taking a fresh one.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>

#include "sim/io/huge_buffer.h"

namespace spume {
namespace {

constexpr size_t kMiB = size_t(1) << 20;

// The pool is process-wide and other tests leave small blocks in it: these tests use sizes of 170 MiB
// and more, which no other test here asks for, each test its own range, and give back what they take.
struct Taken {
  void* block;
  size_t bytes;
};

Taken take(size_t bytes) {
  Taken t{nullptr, 0};
  t.block = scratch_take(bytes, t.bytes);
  return t;
}

TEST(ScratchPool, AFreedBlockIsTakenAgainByARequestItFits) {
  const Taken a = take(176 * kMiB);
  EXPECT_EQ(a.bytes, 176 * kMiB);  // 88 units of 2 MiB, 11 x 8: a size the pool keeps as asked
  EXPECT_EQ(reinterpret_cast<uintptr_t>(a.block) % (2 * kMiB), 0u);
  std::memset(a.block, 0x5A, a.bytes);
  const size_t kept = scratch_pool_kept_bytes();
  scratch_give_back(a.block, a.bytes);
  EXPECT_EQ(scratch_pool_kept_bytes(), kept + a.bytes);
  const Taken b = take(170 * kMiB);  // 85 units, rounded up to 88: the freed block fits
  EXPECT_EQ(b.block, a.block);
  EXPECT_EQ(b.bytes, a.bytes);
  EXPECT_EQ(static_cast<const unsigned char*>(b.block)[b.bytes - 1], 0x5A);
  scratch_give_back(b.block, b.bytes);
}

TEST(ScratchPool, ARequestNoKeptBlockFitsGrowsTheLargestOfAtLeastHalfItsSize) {
  const Taken small = take(240 * kMiB), large = take(352 * kMiB);  // 15 x 8 and 11 x 16 units
  std::memset(small.block, 0x11, small.bytes);
  std::memset(large.block, 0x22, large.bytes);
  scratch_give_back(small.block, small.bytes);
  scratch_give_back(large.block, large.bytes);
  const size_t kept = scratch_pool_kept_bytes();
  // 384 MiB (12 x 16 units): no kept block of 384-768 MiB fits. The 352 MiB block, the largest of
  // at least half the request, grows; its bytes come along, and the rest of the block is new.
  const Taken grown = take(384 * kMiB);
  EXPECT_EQ(grown.bytes, 384 * kMiB);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(grown.block) % (2 * kMiB), 0u);
  const auto* bytes = static_cast<const unsigned char*>(grown.block);
  EXPECT_EQ(bytes[0], 0x22);
  EXPECT_EQ(bytes[large.bytes - 1], 0x22);
  EXPECT_EQ(bytes[large.bytes], 0);  // grown: fresh zero pages past the old end
  EXPECT_EQ(scratch_pool_kept_bytes(), kept - large.bytes);
  // The 240 MiB block stays kept for a request it fits.
  const Taken again = take(240 * kMiB);
  EXPECT_EQ(again.block, small.block);
  scratch_give_back(again.block, again.bytes);
  scratch_give_back(grown.block, grown.bytes);
}

}  // namespace
}  // namespace spume
