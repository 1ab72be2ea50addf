// Large allocations are advised transparent huge pages (sim/core/huge_pages.h): checked against the
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

}  // namespace
}  // namespace spume
