#pragma once
// Reductions whose result does not depend on the thread count: the range is cut into chunks of a
// fixed size, each chunk is summed in index order by one task, and the chunk sums are added serially
// in chunk order. Float sums over a thread-dependent split would change in the last bits.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "sim/core/parallel.h"

namespace spume::fluid {

constexpr size_t kReduceChunk = 512;

// sum over chunks of fn(begin, end) -> double, where fn visits [begin, end) in order.
template <typename Fn>
double chunked_sum(size_t n, Fn&& fn) {
  const size_t chunks = (n + kReduceChunk - 1) / kReduceChunk;
  std::vector<double> partial(chunks, 0.0);
  parallel_for(chunks, 1, [&](size_t b, size_t e) {
    for (size_t c = b; c < e; ++c) partial[c] = fn(c * kReduceChunk, std::min(n, (c + 1) * kReduceChunk));
  });
  double sum = 0.0;
  for (double s : partial) sum += s;
  return sum;
}

// max over chunks of fn(begin, end) (max is exact, so only the chunking is for parallelism).
template <typename Fn>
double chunked_max(size_t n, double init, Fn&& fn) {
  const size_t chunks = (n + kReduceChunk - 1) / kReduceChunk;
  std::vector<double> partial(chunks, init);
  parallel_for(chunks, 1, [&](size_t b, size_t e) {
    for (size_t c = b; c < e; ++c) partial[c] = fn(c * kReduceChunk, std::min(n, (c + 1) * kReduceChunk));
  });
  double m = init;
  for (double s : partial) m = std::max(m, s);
  return m;
}

}  // namespace spume::fluid
