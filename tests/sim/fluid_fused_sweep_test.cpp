// The fused update-then-residual sweep of the Jacobi iterations (sim/fluid/fused_sweep.h): every
// chunk's residual runs exactly once, only after the update has run over its whole reach, and the
// sum is the same for any thread count. Particles here are synthetic: particle i's neighbours are
// the indices within a band of `band` around it, as cell-ordered particles are.
#include <gtest/gtest.h>

#include <atomic>
#include <memory>

#include "sim/core/parallel.h"
#include "sim/fluid/fused_sweep.h"

namespace spume::fluid {
namespace {

struct SweepOutcome {
  double sum = 0.0;
  uint64_t early = 0;   // residual reads of a neighbour the update had not reached yet
  uint64_t updates = 0;
  std::vector<int> residual_runs;  // per chunk
};

SweepOutcome sweep(size_t n, size_t band, int threads) {
  set_thread_count(threads);
  Neighbourhoods nb;
  nb.reach.resize(n);
  for (size_t i = 0; i < n; ++i)
    nb.reach[i] = {uint32_t(i > band ? i - band : 0), uint32_t(std::min(n - 1, i + band))};
  const auto reach = chunk_reach(nb);
  auto updated = std::make_unique<std::atomic<uint8_t>[]>(n);
  for (size_t i = 0; i < n; ++i) updated[i] = 0;
  SweepOutcome out;
  out.residual_runs.assign(reach.size(), 0);
  std::atomic<uint64_t> early{0}, updates{0};
  out.sum = fused_sweep(
      n, reach,
      [&](size_t b, size_t e) {
        for (size_t i = b; i < e; ++i) updated[i] = 1;
        updates += e - b;
      },
      [&](size_t b, size_t e) {
        ++out.residual_runs[b / kReduceChunk];
        double s = 0.0;
        for (size_t i = b; i < e; ++i) {
          // The reach's ends and its middle (the update runs in index order, so gaps would show there).
          for (size_t j : {size_t(nb.reach[i].lowest), i, size_t(nb.reach[i].highest)}) early += updated[j] ? 0 : 1;
          s += 1.0 / double(i + 1);  // a sum whose rounding depends on the order of its terms
        }
        return s;
      });
  out.early = early, out.updates = updates;
  set_thread_count(0);
  return out;
}

TEST(FluidFusedSweep, EveryResidualRunsOnceAfterItsWholeReachWasUpdated) {
  // 300k particles in 586 chunks, a band of 9000 (about two cell layers of a 600k-particle tank): with
  // two or more threads the parts meet inside many chunks' reach, which must wait for the last phase.
  const size_t n = 300000, band = 9000;
  for (int threads : {1, 2, 3, 4}) {
    const SweepOutcome o = sweep(n, band, threads);
    EXPECT_EQ(o.early, 0u) << threads << " threads";
    EXPECT_EQ(o.updates, n) << threads << " threads";
    for (size_t c = 0; c < o.residual_runs.size(); ++c)
      ASSERT_EQ(o.residual_runs[c], 1) << "chunk " << c << ", " << threads << " threads";
  }
}

TEST(FluidFusedSweep, SumIsChunkedInIndexOrderForAnyThreadCount) {
  const size_t n = 100003, band = 3000;
  // The expectation, summed independently: each chunk in index order, then the chunks in order.
  double expected = 0.0;
  for (size_t b = 0; b < n; b += kReduceChunk) {
    double s = 0.0;
    for (size_t i = b; i < std::min(n, b + kReduceChunk); ++i) s += 1.0 / double(i + 1);
    expected += s;
  }
  for (int threads : {1, 2, 4}) EXPECT_EQ(sweep(n, band, threads).sum, expected) << threads << " threads";
}

}  // namespace
}  // namespace spume::fluid
