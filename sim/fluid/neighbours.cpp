#include "sim/fluid/neighbours.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/grid/block_buffer.h"

namespace spume::fluid {
namespace {

// Occupied grid cells per task. The partition depends only on the grid, so every task's output is
// the same for any thread count; tasks cover contiguous particle ranges (particles are in cell order).
constexpr size_t kCellsPerTask = 32;

// Squared distances from (px, py, pz) to the m block points (m a multiple of kLanes) into d2, and the
// indices of those within sqrt(h2) (about 1 in 6) into hit, in block order; returns their count.
// With SSE2 the distances and the comparison run four lanes at a time and only the hits are visited
// (a movemask per four candidates), instead of a scalar pass over every candidate: the compaction was
// the build's largest cost. The arithmetic is the same IEEE operations in the same order either way.
inline size_t candidates_within(const float* xs, const float* ys, const float* zs, size_t m, float px, float py,
                                float pz, float h2, float* d2, uint32_t* hit) {
  size_t hits = 0;
#if defined(__SSE2__)
  const __m128 vx = _mm_set1_ps(px), vy = _mm_set1_ps(py), vz = _mm_set1_ps(pz), vh2 = _mm_set1_ps(h2);
  for (size_t k = 0; k < m; k += 4) {
    const __m128 dx = _mm_sub_ps(_mm_loadu_ps(xs + k), vx);
    const __m128 dy = _mm_sub_ps(_mm_loadu_ps(ys + k), vy);
    const __m128 dz = _mm_sub_ps(_mm_loadu_ps(zs + k), vz);
    const __m128 r2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    _mm_storeu_ps(d2 + k, r2);
    for (unsigned mask = unsigned(_mm_movemask_ps(_mm_cmple_ps(r2, vh2))); mask; mask &= mask - 1)
      hit[hits++] = uint32_t(k) + uint32_t(__builtin_ctz(mask));
  }
#else
  for (size_t k = 0; k < m; ++k) {
    const float dx = xs[k] - px, dy = ys[k] - py, dz = zs[k] - pz;
    d2[k] = dx * dx + dy * dy + dz * dz;
  }
  for (size_t k = 0; k < m; ++k) {  // branch-free compaction
    hit[hits] = uint32_t(k);
    hits += d2[k] <= h2;
  }
#endif
  return hits;
}

#if defined(__x86_64__)
// The same, eight candidates at a time, for processors with AVX2 (m is a multiple of kLanes = 8). The
// lanes do the same IEEE operations (no FMA: AVX2 alone does not enable it), so d2 and the hits are too.
__attribute__((target("avx2"))) size_t candidates_within_avx2(const float* xs, const float* ys, const float* zs,
                                                              size_t m, float px, float py, float pz, float h2,
                                                              float* d2, uint32_t* hit) {
  size_t hits = 0;
  const __m256 vx = _mm256_set1_ps(px), vy = _mm256_set1_ps(py), vz = _mm256_set1_ps(pz), vh2 = _mm256_set1_ps(h2);
  for (size_t k = 0; k < m; k += 8) {
    const __m256 dx = _mm256_sub_ps(_mm256_loadu_ps(xs + k), vx);
    const __m256 dy = _mm256_sub_ps(_mm256_loadu_ps(ys + k), vy);
    const __m256 dz = _mm256_sub_ps(_mm256_loadu_ps(zs + k), vz);
    const __m256 r2 =
        _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
    _mm256_storeu_ps(d2 + k, r2);
    for (unsigned mask = unsigned(_mm256_movemask_ps(_mm256_cmp_ps(r2, vh2, _CMP_LE_OS))); mask; mask &= mask - 1)
      hit[hits++] = uint32_t(k) + uint32_t(__builtin_ctz(mask));
  }
  return hits;
}

const bool kHasAvx2 = __builtin_cpu_supports("avx2");
#endif

// candidates_within on the widest vectors the processor has.
inline size_t candidates_within_best(const float* xs, const float* ys, const float* zs, size_t m, float px, float py,
                                     float pz, float h2, float* d2, uint32_t* hit) {
#if defined(__x86_64__)
  if (kHasAvx2) return candidates_within_avx2(xs, ys, zs, m, px, py, pz, h2, d2, hit);
#endif
  return candidates_within(xs, ys, zs, m, px, py, pz, h2, d2, hit);
}

// For the m squared distances d2 of the pairs within h: s = volume * kernel.grad_factor(r) and
// w = kernel.value(r), r = sqrt(d2). With SSE2 four pairs at a time, both branches of the piecewise
// kernel computed and the right one selected per lane: the same IEEE operations in the same order as
// the scalar CubicSpline calls, hence the same bits, without a mispredicted branch on q <= 1/2 for
// about every other pair. d2, s and w must have room for m rounded up to a multiple of 4.
inline void kernel_terms(const CubicSpline& kernel, float volume, float* d2, size_t m, float* s, float* w) {
#if defined(__SSE2__)
  for (size_t k = m; k % 4 != 0; ++k) d2[k] = 0.0f;
  const __m128 inv_h = _mm_set1_ps(kernel.inv_h), one = _mm_set1_ps(1.0f), half = _mm_set1_ps(0.5f);
  const __m128 zero = _mm_setzero_ps(), sigma = _mm_set1_ps(kernel.sigma), two = _mm_set1_ps(2.0f);
  const __m128 six = _mm_set1_ps(6.0f), three = _mm_set1_ps(3.0f), vol = _mm_set1_ps(volume);
  const __m128 grad_sigma = _mm_set1_ps(kernel.grad_sigma), neg_grad_sigma = _mm_set1_ps(-kernel.grad_sigma);
  auto select = [](__m128 mask, __m128 a, __m128 b) { return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b)); };
  for (size_t k = 0; k < m; k += 4) {
    const __m128 q = _mm_mul_ps(_mm_sqrt_ps(_mm_loadu_ps(d2 + k)), inv_h);
    const __m128 inner = _mm_cmple_ps(q, half), inside = _mm_cmple_ps(q, one), positive = _mm_cmpgt_ps(q, zero);
    const __m128 q2 = _mm_mul_ps(q, q), t = _mm_sub_ps(one, q);
    const __m128 w_inner = _mm_mul_ps(sigma, _mm_add_ps(_mm_mul_ps(six, _mm_sub_ps(_mm_mul_ps(q2, q), q2)), one));
    const __m128 w_outer = _mm_mul_ps(_mm_mul_ps(_mm_mul_ps(_mm_mul_ps(sigma, two), t), t), t);
    const __m128 g_inner = _mm_mul_ps(grad_sigma, _mm_sub_ps(_mm_mul_ps(three, q), two));
    const __m128 g_outer = _mm_and_ps(positive, _mm_div_ps(_mm_mul_ps(_mm_mul_ps(neg_grad_sigma, t), t), q));
    _mm_storeu_ps(w + k, _mm_and_ps(inside, select(inner, w_inner, w_outer)));
    _mm_storeu_ps(s + k, _mm_mul_ps(vol, _mm_and_ps(inside, select(inner, g_inner, g_outer))));
  }
#else
  for (size_t k = 0; k < m; ++k) {
    const float r = std::sqrt(d2[k]);
    s[k] = volume * kernel.grad_factor(r);
    w[k] = kernel.value(r);
  }
#endif
}

}  // namespace

void build_neighbourhoods(const NeighbourGrid& grid, const Boundary& boundary, const CubicSpline& kernel, float volume,
                          Particles& p, Neighbourhoods& nb) {
  const size_t n = p.size();
  const float h = kernel.h, h2 = h * h;
  const NeighbourGrid& bgrid = boundary.grid;
  std::span<const Vec3f> bx = bgrid.sorted_points();
  const std::vector<float>& bvol = boundary.sorted_volume;
  const std::vector<uint8_t>& on_body = boundary.sorted_on_body;
  const size_t cells = grid.occupied_cell_count();
  const size_t tasks = (cells + kCellsPerTask - 1) / kCellsPerTask;
  nb.tasks.resize(tasks);
  nb.counts.resize(2 * n);
  nb.boundary_grad.resize(n);
  nb.reach.resize(n);
  const float eps = 1.0e-6f / h2;

  // One sweep per cell: gather the 27-cell block once (structure of arrays, padded for SIMD), then for
  // each particle of the cell compute all squared distances in a vectorisable loop and keep the
  // pairs within h. Pairs go to task-local buffers in particle order and are copied into place below.
  // Density (the SPH sum of [BK17] plus the boundary term of [AIA12]) and the DFSPH factor
  // alpha_i = 1 / (|sum_j V_j grad W_ij|^2 + sum_j |V_j grad W_ij|^2) (the factor of [BK17] divided by
  // rho_i, as our pressures are p / rho, see pressure.h) come out of the same sweep. Static and
  // kinematic boundary neighbours enter the first sum only: they do not move in response to particle
  // i's pressure. A dynamic body's do, with the body, so they enter the second sum too: otherwise a
  // particle between two bodies, whose pulls cancel, gets a factor without bound (MODEL.md §10).
  parallel_for(tasks, 1, [&](size_t tb, size_t te) {
    BlockBuffer block;
    std::vector<float> d2, hit_d2, hit_s, hit_w;
    std::vector<uint32_t> hit;
    uint32_t boundary_key = NeighbourGrid::kOutside;
    std::array<NeighbourGrid::Range, 9> boundary_rows{};
    for (size_t t = tb; t < te; ++t) {
      Neighbourhoods::Task& task = nb.tasks[t];
      task.pairs.clear();
      task.boundary_pairs.clear();
      const size_t c_end = std::min(cells, (t + 1) * kCellsPerTask);
      for (size_t c = t * kCellsPerTask; c < c_end; ++c) {
        block.gather(grid, grid.occupied_key(c));
        const size_t m = block.size();
        d2.resize(m);
        hit.resize(m);
        hit_d2.resize(m + 4), hit_s.resize(m + 4), hit_w.resize(m + 4);
        const float *bxs = block.x(), *bys = block.y(), *bzs = block.z();
        const uint32_t* index = block.sorted_index();
        for (uint32_t i = grid.cell_begin(c); i < grid.cell_begin(c + 1); ++i) {
          const Vec3f xi = p.x[i];
          const float px = xi.x(), py = xi.y(), pz = xi.z();
          const size_t hits = candidates_within_best(bxs, bys, bzs, m, px, py, pz, h2, d2.data(), hit.data());
          for (size_t c_hit = 0; c_hit < hits; ++c_hit) hit_d2[c_hit] = d2[hit[c_hit]];
          kernel_terms(kernel, volume, hit_d2.data(), hits, hit_s.data(), hit_w.data());
          // Room for every hit first: with no allocation inside the loop the sums stay in registers.
          const size_t first = task.pairs.size();
          task.pairs.resize(first + hits);
          FluidPair* out = task.pairs.data() + first;
          size_t kept = 0;
          uint32_t lowest = uint32_t(i), highest = uint32_t(i);
          float w_sum = kernel.value_at_zero();
          Vec3f g_fluid = Vec3f::Zero();
          float g2_sum = 0.0f;
          for (size_t c_hit = 0; c_hit < hits; ++c_hit) {
            const uint32_t j = index[hit[c_hit]];
            if (j == i) continue;
            const FluidPair q{j, hit_s[c_hit]};
            const Vec3f g = q.g(xi - p.x[j]);
            out[kept++] = q;
            lowest = std::min(lowest, j), highest = std::max(highest, j);
            w_sum += hit_w[c_hit];
            g_fluid += g;
            g2_sum += g.squaredNorm();
          }
          task.pairs.resize(first + kept);
          nb.reach[i] = {lowest, highest};
          const size_t bfirst = task.boundary_pairs.size();
          float bw_sum = 0.0f;
          Vec3f g_boundary = Vec3f::Zero();
          // The boundary points within h, as bgrid.for_each_neighbour visits them; the block's row
          // ranges are looked up once per boundary cell (consecutive particles mostly share one).
          const uint32_t bkey = bgrid.key_of(xi);
          if (bkey != NeighbourGrid::kOutside) {
            if (bkey != boundary_key) {
              boundary_key = bkey;
              boundary_rows = bgrid.block_ranges(bkey);
            }
            for (const NeighbourGrid::Range& row : boundary_rows)
              for (uint32_t k = row.first; k < row.second; ++k) {
                const float dist2 = (bx[k] - xi).squaredNorm();
                if (!(dist2 <= h2)) continue;
                const float r = std::sqrt(dist2);
                const Vec3f g = (bvol[k] * kernel.grad_factor(r)) * (xi - bx[k]);
                task.boundary_pairs.push_back(Pair{k, g.x(), g.y(), g.z()});
                bw_sum += bvol[k] * kernel.value(r);
                g_boundary += g;
                if (on_body[k]) g2_sum += g.squaredNorm();
              }
          }
          nb.counts[i] = uint32_t(task.pairs.size() - first);
          nb.counts[n + i] = uint32_t(task.boundary_pairs.size() - bfirst);
          p.density[i] = volume * w_sum + bw_sum;
          nb.boundary_grad[i] = g_boundary;
          const float denominator = (g_fluid + g_boundary).squaredNorm() + g2_sum;
          p.factor[i] = denominator > eps ? 1.0f / denominator : 0.0f;
        }
      }
    }
  });

  nb.offset.resize(n + 1);
  nb.boundary_offset.resize(n + 1);
  uint64_t total = 0, btotal = 0;
  for (size_t i = 0; i < n; ++i) {
    nb.offset[i] = uint32_t(total);
    nb.boundary_offset[i] = uint32_t(btotal);
    total += nb.counts[i];
    btotal += nb.counts[n + i];
  }
  if (total >= UINT32_MAX || btotal >= UINT32_MAX) fail("fluid solver: more than 2^32 neighbour pairs");
  nb.offset[n] = uint32_t(total);
  nb.boundary_offset[n] = uint32_t(btotal);
  nb.pairs.resize(total);
  nb.boundary_pairs.resize(btotal);
  parallel_for(tasks, 1, [&](size_t tb, size_t te) {
    for (size_t t = tb; t < te; ++t) {
      const uint32_t first = grid.cell_begin(t * kCellsPerTask);
      const Neighbourhoods::Task& task = nb.tasks[t];
      if (!task.pairs.empty())
        std::memcpy(nb.pairs.data() + nb.offset[first], task.pairs.data(), task.pairs.size() * sizeof(FluidPair));
      if (!task.boundary_pairs.empty())
        std::memcpy(nb.boundary_pairs.data() + nb.boundary_offset[first], task.boundary_pairs.data(),
                    task.boundary_pairs.size() * sizeof(Pair));
    }
  });
}

}  // namespace spume::fluid
