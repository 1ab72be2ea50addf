#include "sim/io/huge_buffer.h"

#include <algorithm>
#include <mutex>
#include <vector>

namespace spume {
namespace {

constexpr size_t kHuge = size_t(2) << 20;

// 2 MiB units rounded up to 8..15 x a power of two (at most 1/8 more than asked).
size_t block_size(size_t bytes) {
  size_t units = std::max<size_t>(1, (bytes + kHuge - 1) / kHuge);
  int shift = 0;
  while ((units >> shift) >= 16) ++shift;
  units = ((units + (size_t(1) << shift) - 1) >> shift) << shift;
  return units * kHuge;
}

struct Pool {
  std::mutex mutex;
  std::vector<std::pair<void*, size_t>> kept;  // oldest first
  size_t kept_bytes = 0;
};

Pool& pool() {
  static Pool* p = new Pool;  // never destroyed: buffers may be freed during static destruction
  return *p;
}

}  // namespace

void* scratch_take(size_t bytes, size_t& block_bytes) {
  const size_t want = block_size(bytes);
  {
    Pool& p = pool();
    std::lock_guard lock(p.mutex);
    auto best = p.kept.end();
    for (auto it = p.kept.begin(); it != p.kept.end(); ++it)
      if (it->second >= want && it->second <= 2 * want && (best == p.kept.end() || it->second < best->second))
        best = it;
    if (best != p.kept.end()) {
      void* block = best->first;
      block_bytes = best->second;
      p.kept_bytes -= block_bytes;
      p.kept.erase(best);
      return block;
    }
  }
  void* block = std::aligned_alloc(kHuge, want);
  if (!block) throw std::bad_alloc();
  madvise(block, want, MADV_HUGEPAGE);  // advice only: without huge pages it is an ordinary buffer
  block_bytes = want;
  return block;
}

void scratch_give_back(void* block, size_t block_bytes) {
  std::vector<void*> release;
  {
    Pool& p = pool();
    std::lock_guard lock(p.mutex);
    p.kept.emplace_back(block, block_bytes);
    p.kept_bytes += block_bytes;
    while (p.kept_bytes > kScratchPoolBytes) {
      release.push_back(p.kept.front().first);
      p.kept_bytes -= p.kept.front().second;
      p.kept.erase(p.kept.begin());
    }
  }
  for (void* b : release) std::free(b);
}

size_t scratch_pool_kept_bytes() {
  Pool& p = pool();
  std::lock_guard lock(p.mutex);
  return p.kept_bytes;
}

}  // namespace spume
