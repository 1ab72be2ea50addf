// The pool behind HugeBuffer (io/huge_buffer.h): a freed block is taken again by a request it fits,
// a block written in part goes back to an owner that writes in part before one that writes whole
// (and the other way round), and a request no kept block fits grows the largest kept block of at
// least half its size, keeping its pages (so only the growth is fresh memory), instead of taking a
// fresh one. A request under 2 MiB is served in ordinary pages, so a small frame's columns do not
// each hold a whole 2 MiB page.
#include <gtest/gtest.h>

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "sim/io/huge_buffer.h"

namespace spume {
namespace {

constexpr size_t kMiB = size_t(1) << 20;

// The pool is process-wide and other tests leave blocks in it: each test here starts from an empty
// pool.
class ScratchPool : public ::testing::Test {
 protected:
  void SetUp() override {
    scratch_pool_release();
    ASSERT_EQ(scratch_pool_kept_bytes(), 0u);
  }
};

struct Taken {
  void* block;
  size_t bytes;
};

Taken take(size_t bytes, BlockWrites writes = BlockWrites::Whole) {
  Taken t{nullptr, 0};
  t.block = scratch_take(bytes, t.bytes, writes);
  return t;
}

TEST_F(ScratchPool, AFreedBlockIsTakenAgainByARequestItFits) {
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

// Pages of [p, p + bytes) resident now (mincore).
size_t resident_pages(void* p, size_t bytes) {
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  std::vector<unsigned char> in((bytes + page - 1) / page);
  if (mincore(p, bytes, in.data()) != 0) return 0;
  return size_t(std::count_if(in.begin(), in.end(), [](unsigned char c) { return c & 1; }));
}

TEST_F(ScratchPool, ARequestUnderTwoMiBTakesOrdinaryPages) {
  // 100 KiB: two units of 64 KiB; 1.5 MiB: 24 units, a multiple of 2 (12 x 2^1) kept as asked.
  const Taken a = take(100 << 10), b = take(1536 << 10);
  EXPECT_EQ(a.bytes, size_t(128) << 10);
  EXPECT_EQ(b.bytes, size_t(1536) << 10);
  // One byte written maps one page, not the 2 MiB page around it.
  static_cast<unsigned char*>(a.block)[0] = 1;
  static_cast<unsigned char*>(b.block)[0] = 1;
  const size_t page = size_t(sysconf(_SC_PAGESIZE));
  EXPECT_EQ(resident_pages(a.block, a.bytes), 1u);
  EXPECT_EQ(resident_pages(b.block, b.bytes), 1u) << "of " << b.bytes / page;
  // 2 MiB and more are still whole 2 MiB units at a 2 MiB boundary.
  const Taken c = take(2 * kMiB + 1);
  EXPECT_EQ(c.bytes, 4 * kMiB);
  EXPECT_EQ(reinterpret_cast<uintptr_t>(c.block) % (2 * kMiB), 0u);
  for (const Taken& t : {a, b, c}) scratch_give_back(t.block, t.bytes);
}

TEST_F(ScratchPool, ARequestNoKeptBlockFitsGrowsTheLargestOfAtLeastHalfItsSize) {
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

TEST_F(ScratchPool, EachKindOfBlockGoesBackToItsOwnKindOfOwnerFirst) {
  // Two blocks of 208 MiB (13 x 8 units of 2 MiB), one given back by an owner that writes whole, one by
  // an owner that writes in part, in both orders: the order of the pool's list must not decide.
  for (bool in_part_first : {true, false}) {
    scratch_pool_release();
    const Taken whole = take(208 * kMiB), in_part = take(208 * kMiB, BlockWrites::InPart);
    ASSERT_NE(whole.block, in_part.block);
    if (in_part_first) scratch_give_back(in_part.block, in_part.bytes, BlockWrites::InPart);
    scratch_give_back(whole.block, whole.bytes, BlockWrites::Whole);
    if (!in_part_first) scratch_give_back(in_part.block, in_part.bytes, BlockWrites::InPart);
    const Taken sort_scratch = take(200 * kMiB);
    EXPECT_EQ(sort_scratch.block, whole.block) << in_part_first;
    const Taken cache = take(200 * kMiB, BlockWrites::InPart);
    EXPECT_EQ(cache.block, in_part.block) << in_part_first;
    // With only the other kind kept, a request still takes it rather than fresh memory.
    scratch_give_back(cache.block, cache.bytes, BlockWrites::InPart);
    const Taken second_scratch = take(200 * kMiB);
    EXPECT_EQ(second_scratch.block, in_part.block) << in_part_first;
    scratch_give_back(sort_scratch.block, sort_scratch.bytes);
    scratch_give_back(second_scratch.block, second_scratch.bytes);
  }
}

TEST_F(ScratchPool, AGrowingRequestGrowsABlockOfItsOwnKindFirst) {
  // 224 MiB blocks of both kinds (14 x 8 units of 2 MiB); 240 MiB (15 x 8) fits neither, so one is grown.
  for (BlockWrites writes : {BlockWrites::Whole, BlockWrites::InPart}) {
    scratch_pool_release();
    const Taken whole = take(224 * kMiB), in_part = take(224 * kMiB, BlockWrites::InPart);
    std::memset(whole.block, 0x33, whole.bytes);
    std::memset(in_part.block, 0x44, in_part.bytes);
    scratch_give_back(in_part.block, in_part.bytes, BlockWrites::InPart);
    scratch_give_back(whole.block, whole.bytes, BlockWrites::Whole);
    const Taken grown = take(240 * kMiB, writes);
    EXPECT_EQ(grown.bytes, 240 * kMiB);
    EXPECT_EQ(static_cast<const unsigned char*>(grown.block)[0], writes == BlockWrites::Whole ? 0x33 : 0x44);
    const Taken other = take(224 * kMiB, writes == BlockWrites::Whole ? BlockWrites::InPart : BlockWrites::Whole);
    EXPECT_EQ(other.block, writes == BlockWrites::Whole ? in_part.block : whole.block);
    scratch_give_back(grown.block, grown.bytes, writes);
    scratch_give_back(other.block, other.bytes);
  }
}

// The cap is a third of the machine's memory (MemTotal), at least 2 GiB: a 100M-particle frame's
// encoder takes about 7 GiB of blocks, which a fixed 2 GiB cap handed back to be cleared again
// every frame.
TEST_F(ScratchPool, TheCapIsAThirdOfTheMachinesMemoryAndAtLeastTwoGiB) {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  size_t kib = 0;
  while (meminfo >> key && key != "MemTotal:") meminfo.ignore(256, '\n');
  ASSERT_TRUE(meminfo >> kib);
  const size_t third = kib * 1024 / 3;
  EXPECT_NEAR(double(scratch_pool_cap()), double(std::max(size_t(2) << 30, third)), 3.0 * 4096);
}

// Blocks given back beyond the cap: the oldest are handed to the system until the rest fit, so the
// pool keeps at most the cap, and (blocks of a quarter of it) at least half of it. The blocks are
// address space only: nothing here writes them.
TEST_F(ScratchPool, BlocksBeyondTheCapAreReleasedOldestFirst) {
  const size_t quarter = scratch_pool_cap() / 4;
  std::vector<Taken> taken;
  for (int k = 0; k < 5; ++k) taken.push_back(take(quarter - 4 * kMiB));
  for (const Taken& t : taken) scratch_give_back(t.block, t.bytes);
  EXPECT_LE(scratch_pool_kept_bytes(), scratch_pool_cap());
  EXPECT_GE(scratch_pool_kept_bytes(), scratch_pool_cap() / 2);
  // The blocks kept are the newest: taken again (as many as are kept), they are the last given back.
  const size_t kept = scratch_pool_kept_bytes() / taken[0].bytes;
  ASSERT_GE(kept, 1u);
  std::vector<void*> again, newest;
  for (size_t k = 0; k < kept; ++k) {
    again.push_back(take(quarter - 4 * kMiB).block);
    newest.push_back(taken[taken.size() - kept + k].block);
  }
  std::sort(again.begin(), again.end());
  std::sort(newest.begin(), newest.end());
  EXPECT_EQ(again, newest);
  for (void* block : again) scratch_give_back(block, taken[0].bytes);
  scratch_pool_release();
}

}  // namespace
}  // namespace spume
