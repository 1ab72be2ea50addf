#pragma once
// Two passes over the particles in one sweep, so that the pair lists stream from memory once instead
// of twice. A Jacobi iteration is a velocity update (each particle reads its neighbours' pressures)
// then a residual (each particle reads its neighbours' new velocities): the residual of a chunk of
// particles may run as soon as the update has run over every particle within its reach. Particles are
// in grid-cell order, so that reach ends a few cell layers ahead, and the chunk's pairs, read by the
// update a moment before, are still in the last-level cache when the residual reads them again.
//
// Each thread sweeps one contiguous part: update a chunk, then every earlier chunk of its part whose
// reach is covered; chunks whose reach crosses into another part wait until every part has finished
// updating. Each particle's arithmetic is that of the two separate passes, and each chunk's residual
// is summed in index order, so the results do not depend on the thread count.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "sim/core/parallel.h"
#include "sim/fluid/neighbours.h"
#include "sim/fluid/reduce.h"

namespace spume::fluid {

// The lowest and highest particle index among the neighbours of each chunk of kReduceChunk particles.
inline std::vector<Neighbourhoods::Reach> chunk_reach(const Neighbourhoods& nb) {
  const size_t n = nb.reach.size(), chunks = (n + kReduceChunk - 1) / kReduceChunk;
  std::vector<Neighbourhoods::Reach> out(chunks);
  parallel_for(chunks, 64, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      Neighbourhoods::Reach r = nb.reach[c * kReduceChunk];
      for (size_t i = c * kReduceChunk + 1; i < std::min(n, (c + 1) * kReduceChunk); ++i)
        r.lowest = std::min(r.lowest, nb.reach[i].lowest), r.highest = std::max(r.highest, nb.reach[i].highest);
      out[c] = r;
    }
  });
  return out;
}

// update(begin, end) over all n particles, then residual(begin, end) -> double over every chunk of
// kReduceChunk; returns the chunk sums added in chunk order (as chunked_sum does).
template <typename Update, typename Residual>
double fused_sweep(size_t n, const std::vector<Neighbourhoods::Reach>& reach, Update&& update, Residual&& residual) {
  const size_t chunks = (n + kReduceChunk - 1) / kReduceChunk;
  auto chunk_end = [&](size_t c) { return std::min(n, (c + 1) * kReduceChunk); };
  std::vector<double> partial(chunks, 0.0);
  // One part a thread, of at least 8 chunks: smaller ones would leave most residuals to the last phase.
  const size_t parts = std::clamp<size_t>(chunks / 8, 1, size_t(thread_count()));
  std::vector<std::vector<size_t>> waiting(parts);
  parallel_for(parts, 1, [&](size_t pb, size_t pe) {
    for (size_t part = pb; part < pe; ++part) {
      const size_t first = chunks * part / parts, last = chunks * (part + 1) / parts;
      const size_t begin = first * kReduceChunk, end = chunk_end(last - 1);
      size_t next = first;  // the next chunk whose residual is due
      for (size_t c = first; c < last; ++c) {
        update(c * kReduceChunk, chunk_end(c));
        const size_t updated_end = chunk_end(c);
        for (; next <= c; ++next) {
          if (reach[next].lowest < begin) {
            waiting[part].push_back(next);
          } else if (reach[next].highest < updated_end) {
            partial[next] = residual(next * kReduceChunk, chunk_end(next));
          } else {
            break;
          }
        }
      }
      for (; next < last; ++next) {
        if (reach[next].highest < end && reach[next].lowest >= begin)
          partial[next] = residual(next * kReduceChunk, chunk_end(next));
        else
          waiting[part].push_back(next);
      }
    }
  });
  std::vector<size_t> rest;
  for (const auto& w : waiting) rest.insert(rest.end(), w.begin(), w.end());
  parallel_for(rest.size(), 1, [&](size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) partial[rest[k]] = residual(rest[k] * kReduceChunk, chunk_end(rest[k]));
  });
  double sum = 0.0;
  for (double s : partial) sum += s;
  return sum;
}

}  // namespace spume::fluid
