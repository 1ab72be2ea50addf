#pragma once
// Transparent huge pages for large arrays. On a virtual machine a page fault is expensive, and a
// 2 MiB page costs one fault where 4 KiB pages cost 512 (tests/bench/RESULTS.md §4). Linux gives
// 2 MiB pages to memory advised so when THP runs in madvise mode (Debian's default), and to all
// anonymous memory in "always" mode.
#include <sys/mman.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <new>
#include <vector>

#include "sim/core/out_of_memory.h"

namespace spume {

// Asks for 2 MiB pages over the whole 2 MiB pages inside [p, p + bytes). Advice only, and only for
// pages not yet touched (fresh memory, such as a large block just allocated); failure is harmless.
inline void advise_huge_pages(void* p, size_t bytes) {
  constexpr uintptr_t kHuge = uintptr_t(2) << 20;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(p) + kHuge - 1) & ~(kHuge - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(p) + bytes) & ~(kHuge - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

// Blocks this large are advised; a smaller one cannot hold more than a 2 MiB page or two.
constexpr size_t kHugePageRequestBytes = size_t(4) << 20;

// Makes room in v for n elements, its contents kept. A new block of kHugePageRequestBytes or more is
// advised into 2 MiB pages before anything is written to it. For arrays that are fresh memory again and
// again: the diffuse stage's grow with the particle count, frame after frame, and their page faults were
// a large share of a 15M frame. Not for arrays allocated once: the fluid solver ran slower in huge pages
// (tests/bench/RESULTS.md §4). A failure records its size for the out-of-memory message.
template <typename T>
void reserve_in_huge_pages(std::vector<T>& v, size_t n) {
  if (n <= v.capacity()) return;
  std::vector<T> grown;
  try {
    grown.reserve(n);
  } catch (const std::bad_alloc&) {
    record_failed_allocation(uint64_t(n) * sizeof(T));
    throw;
  }
  if (n * sizeof(T) >= kHugePageRequestBytes) advise_huge_pages(grown.data(), n * sizeof(T));
  grown.insert(grown.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
  v.swap(grown);
}

// Bytes an array holds (its capacity, not its size): what freeing it would give back.
template <typename T>
size_t held_bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

// The capacity a growing array takes: an eighth more than it had, not the doubling std::vector does.
// The diffuse stage's arrays grow with its particle count a little at a time, frame after frame;
// doubled, they reserved up to twice what a frame used (tests/bench/RESULTS.md §17.2).
inline size_t grown_capacity(size_t capacity, size_t n) { return std::max(n, capacity + capacity / 8); }

// v.resize(n), growing geometrically (grown_capacity) into a block advised as above; contents kept.
template <typename T>
void resize_in_huge_pages(std::vector<T>& v, size_t n) {
  if (n > v.capacity()) reserve_in_huge_pages(v, grown_capacity(v.capacity(), n));
  v.resize(n);
}

// v.resize(n) for an array its owner writes whole after: when it must grow, the old block is freed
// before the new one is taken, so the two are never held at once.
template <typename T>
void resize_discarding_in_huge_pages(std::vector<T>& v, size_t n) {
  if (n > v.capacity()) {
    const size_t capacity = grown_capacity(v.capacity(), n);
    std::vector<T>().swap(v);
    reserve_in_huge_pages(v, capacity);
  }
  v.resize(n);
}

}  // namespace spume
