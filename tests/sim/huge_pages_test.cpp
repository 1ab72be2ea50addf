// Large arrays are advised transparent huge pages (sim/core/huge_pages.h): checked against the
// kernel's own account of the mapping (the "hg" flag of /proc/self/smaps), not against the code.
#include <gtest/gtest.h>
#include <sys/mman.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "sim/core/huge_pages.h"
#include "tests/support/huge_page_flags.h"

namespace spume {
namespace {

using testing::advised;
using testing::kernel_has_huge_pages;
using testing::vm_flags_at;

constexpr size_t kMiB = size_t(1) << 20;

TEST(HugePages, AdviceCoversTheWhole2MiBPagesInsideTheRangeAndNothingElse) {
  if (!kernel_has_huge_pages()) GTEST_SKIP() << "no transparent huge pages in this kernel";
  const size_t bytes = 16 * kMiB;
  char* map = static_cast<char*>(mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0));
  ASSERT_NE(map, MAP_FAILED);
  // The range [1, 6) MiB past a 2 MiB boundary holds two whole 2 MiB pages, [2, 6) MiB; the
  // partial ones at either end must stay as they were.
  char* boundary = reinterpret_cast<char*>((reinterpret_cast<uintptr_t>(map) + 2 * kMiB - 1) & ~(2 * kMiB - 1));
  advise_huge_pages(boundary + 1 * kMiB, 5 * kMiB);
  EXPECT_FALSE(advised(boundary + 1 * kMiB + 4096));
  EXPECT_TRUE(advised(boundary + 2 * kMiB));
  EXPECT_TRUE(advised(boundary + 6 * kMiB - 1));
  EXPECT_FALSE(advised(boundary + 6 * kMiB));
  munmap(map, bytes);
}

// A large array grown through resize_in_huge_pages is advised, keeps its elements and grows as
// std::vector does; a plain vector of the same size is not advised, so the flag is the advice's.
TEST(HugePages, ArraysGrownInHugePagesAreAdvisedAndKeepTheirElements) {
  if (!kernel_has_huge_pages()) GTEST_SKIP() << "no transparent huge pages in this kernel";
  std::vector<uint32_t> column(1000);
  for (size_t i = 0; i < column.size(); ++i) column[i] = uint32_t(3 * i + 1);
  // 64 MiB: above glibc's largest mmap threshold, so the block is a mapping of its own.
  resize_in_huge_pages(column, 16 * kMiB);
  ASSERT_EQ(column.size(), 16 * kMiB);
  for (size_t i = 0; i < 1000; ++i) ASSERT_EQ(column[i], uint32_t(3 * i + 1)) << i;
  for (size_t i = 1000; i < column.size(); i += 4099) ASSERT_EQ(column[i], 0u) << i;
  const char* middle = reinterpret_cast<const char*>(column.data()) + 32 * kMiB;
  EXPECT_TRUE(advised(middle)) << vm_flags_at(middle);
  // Growing by one element at a time would copy the array each time: it grows by an eighth (not the
  // doubling that left the diffuse stage's arrays up to half empty).
  resize_in_huge_pages(column, 16 * kMiB + 1);
  EXPECT_EQ(column.capacity(), 18 * kMiB);
  EXPECT_EQ(column[999], 3u * 999 + 1);
  // An array written whole after is grown the same way; what it held within its size is kept when it
  // does not grow.
  std::vector<uint32_t> scratch(1000, 7u);
  resize_discarding_in_huge_pages(scratch, 500);
  resize_discarding_in_huge_pages(scratch, 900);
  EXPECT_EQ(scratch[499], 7u);
  resize_discarding_in_huge_pages(scratch, 1001);
  EXPECT_EQ(scratch.size(), 1001u);
  EXPECT_EQ(scratch.capacity(), 1125u);

  std::vector<uint32_t> plain;
  plain.reserve(16 * kMiB);
  EXPECT_FALSE(advised(reinterpret_cast<const char*>(plain.data()) + 32 * kMiB));
  // Small arrays are left alone: they cannot hold a whole 2 MiB page worth the advice.
  std::vector<uint32_t> small;
  reserve_in_huge_pages(small, 1000);
  EXPECT_GE(small.capacity(), 1000u);
}

}  // namespace
}  // namespace spume
