// The spume command's operator new (render/app/large_block_operator_new.cpp): it advises large blocks
// huge pages while a stage asks for it, checked against the kernel's own account of the mapping (the "hg"
// flag of /proc/self/smaps). A binary of its own, since a replacement operator new is a process-wide
// choice that the other test binaries must not make.
#include <gtest/gtest.h>
#include <sys/mman.h>

#include <cstdint>
#include <new>
#include <string>
#include <vector>

#include "sim/core/huge_pages.h"
#include "sim/core/sanitizers.h"
#include "tests/support/huge_page_flags.h"

namespace spume {
namespace {

using testing::advised;
using testing::kernel_has_huge_pages;
using testing::vm_flags_at;

constexpr size_t kMiB = size_t(1) << 20;

TEST(HugePages, OperatorNewAdvisesLargeBlocksOnlyWhileAStageAsks) {
  if (!kernel_has_huge_pages()) GTEST_SKIP() << "no transparent huge pages in this kernel";
  if (kAddressSanitizer) GTEST_SKIP() << "AddressSanitizer's operator new replaces spume's in this build";
  // 64 MiB: above glibc's largest mmap threshold, so each block is a mapping of its own.
  std::vector<float> before;
  before.reserve(16 * kMiB);
  EXPECT_FALSE(advised(reinterpret_cast<const char*>(before.data()) + 32 * kMiB));
  std::vector<float> column;
  {
    const HugePagesForLargeBlocks scope;
    column.reserve(16 * kMiB);
  }
  const char* middle = reinterpret_cast<const char*>(column.data()) + 32 * kMiB;
  EXPECT_TRUE(advised(middle)) << vm_flags_at(middle);
  std::vector<float> after;
  after.reserve(16 * kMiB);
  EXPECT_FALSE(advised(reinterpret_cast<const char*>(after.data()) + 32 * kMiB));
  // A plain mapping of the same size is not advised: the flag is the advice's, not the kernel's default.
  const size_t bytes = 64 * kMiB;
  void* map = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(map, MAP_FAILED);
  EXPECT_FALSE(advised(static_cast<char*>(map) + 32 * kMiB));
  munmap(map, bytes);
}

}  // namespace
}  // namespace spume
