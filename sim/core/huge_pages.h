#pragma once
// Transparent huge pages for large arrays. On a virtual machine a page fault is expensive, and a
// 2 MiB page costs one fault where 4 KiB pages cost 512 (tests/bench/RESULTS.md §4). Linux gives
// 2 MiB pages to memory advised so when THP runs in madvise mode (Debian's default), and to all
// anonymous memory in "always" mode.
#include <sys/mman.h>

#include <cstddef>
#include <cstdint>

namespace spume {

// Asks for 2 MiB pages over the whole 2 MiB pages inside [p, p + bytes). Advice only, and only for
// pages not yet touched (fresh memory, such as a large block just allocated); failure is harmless.
inline void advise_huge_pages(void* p, size_t bytes) {
  constexpr uintptr_t kHuge = uintptr_t(2) << 20;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(p) + kHuge - 1) & ~(kHuge - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(p) + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

// While one of these lives (on any thread), the spume command's operator new
// (render/app/large_block_operator_new.cpp) advises huge pages for every block of kHugePageRequestBytes or
// more; in other executables it does nothing. For stages whose large arrays are fresh memory
// again and again: the diffuse stage's grow with the particle count, frame after frame, and their
// page faults were a large share of a 15M frame. Not for the whole program: the fluid solver
// allocates its arrays once, and ran slower in huge pages (tests/bench/RESULTS.md §3.2).
class HugePagesForLargeBlocks {
 public:
  HugePagesForLargeBlocks();
  ~HugePagesForLargeBlocks();
  HugePagesForLargeBlocks(const HugePagesForLargeBlocks&) = delete;
  HugePagesForLargeBlocks& operator=(const HugePagesForLargeBlocks&) = delete;

  static bool active();
};

constexpr size_t kHugePageRequestBytes = size_t(4) << 20;

}  // namespace spume
