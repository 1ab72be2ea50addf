#pragma once
// The one seam between spume and its thread pool (oneTBB). Every parallel loop in spume writes each
// output element from exactly one iteration, so results do not depend on how ranges are split.
#include <cstddef>
#include <algorithm>
#include <memory>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace spume {

// Limit the worker threads for the rest of the process; 0 means one per core.
void set_thread_count(int threads);
int thread_count();

// fn(begin, end) over [0, n) in chunks of at least `grain` items.
template <typename Fn>
void parallel_for(size_t n, size_t grain, Fn&& fn) {
  if (n == 0) return;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain ? grain : 1),
                    [&](const tbb::blocked_range<size_t>& r) { fn(r.begin(), r.end()); });
}

// Exclusive prefix sum of counts into offsets (offsets.size() == counts.size() + 1). Serial: it is
// memory-bound and cheap next to the work that produces the counts, and it must be exact.
template <typename Count, typename Offset>
void exclusive_scan(const Count* counts, size_t n, Offset* offsets) {
  Offset sum = 0;
  for (size_t i = 0; i < n; ++i) {
    offsets[i] = sum;
    sum += Offset(counts[i]);
  }
  offsets[n] = sum;
}

// Stable parallel selection: emit(i, k) for every i in [0, n) with keep(i), where k numbers the kept
// indices in increasing order of i. Returns how many were kept. keep(i) is called twice per index (a
// counting pass, then the emitting pass), so it must be cheap and give the same answer both times.
// The chunks are fixed by n alone and each k is exact, so the result is the same for any thread count.
template <typename Keep, typename Emit>
size_t parallel_select(size_t n, Keep&& keep, Emit&& emit) {
  if (n == 0) return 0;
  const size_t chunk_count = std::clamp<size_t>(n / (1 << 14), 1, 1024);
  const size_t chunk = (n + chunk_count - 1) / chunk_count;
  std::vector<size_t> kept(chunk_count + 1, 0);
  parallel_for(chunk_count, 1, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      size_t count = 0;
      for (size_t i = c * chunk, end = std::min(n, i + chunk); i < end; ++i) count += keep(i) ? 1 : 0;
      kept[c] = count;
    }
  });
  std::vector<size_t> first(chunk_count + 1);
  exclusive_scan(kept.data(), chunk_count, first.data());
  parallel_for(chunk_count, 1, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      size_t k = first[c];
      for (size_t i = c * chunk, end = std::min(n, i + chunk); i < end; ++i)
        if (keep(i)) emit(i, k++);
    }
  });
  return first[chunk_count];
}

}  // namespace spume
