#include "sim/io/huge_buffer.h"

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <new>
#include <utility>
#include <vector>

#include "sim/core/out_of_memory.h"

namespace spume {
namespace {

constexpr size_t kHuge = size_t(2) << 20;
// Requests under a 2 MiB page take 64 KiB units of ordinary pages: in 2 MiB pages each of a small
// frame's cache columns held a whole page, 12 MiB of a dam break simulate that makes no particles.
constexpr size_t kSmallUnit = size_t(64) << 10;

// Units (2 MiB, or 64 KiB under 2 MiB) rounded up to 8..15 x a power of two (at most 1/8 more than
// asked).
size_t block_size(size_t bytes) {
  const size_t unit = bytes >= kHuge ? kHuge : kSmallUnit;
  size_t units = std::max<size_t>(1, (bytes + unit - 1) / unit);
  int shift = 0;
  while ((units >> shift) >= 16) ++shift;
  units = ((units + (size_t(1) << shift) - 1) >> shift) << shift;
  return units * unit;
}

struct Kept {
  void* block;
  size_t bytes;
  BlockWrites writes;
};

struct Pool {
  std::mutex mutex;
  std::vector<Kept> kept;  // oldest first
  size_t kept_bytes = 0;
};

Pool& pool() {
  static Pool* p = new Pool;  // never destroyed: buffers may be freed during static destruction
  return *p;
}

// A fresh block of `bytes` (block_size's): a multiple of 2 MiB at a 2 MiB boundary, advised 2 MiB
// pages, or a smaller one in ordinary pages; null when the address space is short.
void* map_block(size_t bytes) {
  if (bytes % kHuge != 0) {
    void* small = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    return small == MAP_FAILED ? nullptr : small;
  }
  void* region = mmap(nullptr, bytes + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (region == MAP_FAILED) return nullptr;
  char* start = static_cast<char*>(region);
  char* block = reinterpret_cast<char*>((reinterpret_cast<uintptr_t>(start) + kHuge - 1) & ~(kHuge - 1));
  if (block > start) munmap(start, size_t(block - start));
  if (block + bytes < start + bytes + kHuge) munmap(block + bytes, size_t(start + bytes + kHuge - (block + bytes)));
  madvise(block, bytes, MADV_HUGEPAGE);  // advice only: without huge pages it is an ordinary buffer
  return block;
}

// `block` (of old_bytes) grown to new_bytes at a new 2 MiB boundary: its pages move over as they
// are, 2 MiB ones included, and only the growth is fresh memory for the kernel to clear. Null when
// it cannot be moved; `block` is then as it was.
void* grow_block(void* block, size_t old_bytes, size_t new_bytes) {
  char* target = static_cast<char*>(map_block(new_bytes));  // a 2 MiB-aligned place, never touched
  if (!target) return nullptr;
  void* moved = mremap(block, old_bytes, new_bytes, MREMAP_MAYMOVE | MREMAP_FIXED, target);
  if (moved == MAP_FAILED) {
    munmap(target, new_bytes);
    return nullptr;
  }
  if (new_bytes % kHuge == 0) madvise(moved, new_bytes, MADV_HUGEPAGE);
  return moved;
}

}  // namespace

size_t scratch_pool_cap() {
  static const size_t cap = [] {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    const size_t third = pages > 0 && page > 0 ? size_t(pages) * size_t(page) / 3 : 0;
    return std::max(size_t(2) << 30, third);
  }();
  return cap;
}

void* scratch_take(size_t bytes, size_t& block_bytes, BlockWrites writes) {
  const size_t want = block_size(bytes);
  Kept grow{nullptr, 0, writes};
  {
    Pool& p = pool();
    std::lock_guard lock(p.mutex);
    // The best kept block by `better` among those `eligible`, of the request's kind if there is one.
    auto pick = [&](auto eligible, auto better) {
      auto best = p.kept.end();
      for (bool own_kind : {true, false}) {
        for (auto it = p.kept.begin(); it != p.kept.end(); ++it)
          if ((it->writes == writes) == own_kind && eligible(*it) && (best == p.kept.end() || better(*it, *best)))
            best = it;
        if (best != p.kept.end()) break;
      }
      return best;
    };
    auto taken = [&](auto it) {
      const Kept k = *it;
      p.kept_bytes -= k.bytes;
      p.kept.erase(it);
      return k;
    };
    auto fits = pick([&](const Kept& k) { return k.bytes >= want && k.bytes <= 2 * want; },
                     [](const Kept& a, const Kept& b) { return a.bytes < b.bytes; });
    if (fits != p.kept.end()) {
      const Kept k = taken(fits);
      block_bytes = k.bytes;
      return k.block;
    }
    // None fits: a frame's arrays grow with its particle count, so the largest kept block of at
    // least half the size (most likely last frame's array of the same kind) is grown instead.
    auto half = pick([&](const Kept& k) { return k.bytes < want && k.bytes * 2 >= want; },
                     [](const Kept& a, const Kept& b) { return a.bytes > b.bytes; });
    if (half != p.kept.end()) grow = taken(half);
  }
  if (grow.block) {
    if (void* block = grow_block(grow.block, grow.bytes, want)) {
      block_bytes = want;
      return block;
    }
    munmap(grow.block, grow.bytes);
  }
  void* block = map_block(want);
  if (!block) {
    record_failed_allocation(want);
    throw std::bad_alloc();
  }
  block_bytes = want;
  return block;
}

void scratch_give_back(void* block, size_t block_bytes, BlockWrites writes) {
  std::vector<Kept> release;
  {
    Pool& p = pool();
    std::lock_guard lock(p.mutex);
    p.kept.push_back({block, block_bytes, writes});
    p.kept_bytes += block_bytes;
    while (p.kept_bytes > scratch_pool_cap()) {
      release.push_back(p.kept.front());
      p.kept_bytes -= p.kept.front().bytes;
      p.kept.erase(p.kept.begin());
    }
  }
  for (const Kept& k : release) munmap(k.block, k.bytes);
}

void scratch_pool_release() {
  std::vector<Kept> release;
  {
    Pool& p = pool();
    std::lock_guard lock(p.mutex);
    release.swap(p.kept);
    p.kept_bytes = 0;
  }
  for (const Kept& k : release) munmap(k.block, k.bytes);
}

size_t scratch_pool_kept_bytes() {
  Pool& p = pool();
  std::lock_guard lock(p.mutex);
  return p.kept_bytes;
}

}  // namespace spume
