#pragma once
// The one seam between spume and its thread pool (oneTBB). Every parallel loop in spume writes each
// output element from exactly one iteration, so results do not depend on how ranges are split.
#include <cstddef>
#include <memory>

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

}  // namespace spume
