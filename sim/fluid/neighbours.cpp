#include "sim/fluid/neighbours.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
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

}  // namespace

void build_neighbourhoods(const NeighbourGrid& grid, const Boundary& boundary, const CubicSpline& kernel, float volume,
                          Particles& p, Neighbourhoods& nb) {
  const size_t n = p.size();
  const float h = kernel.h, h2 = h * h;
  const NeighbourGrid& bgrid = boundary.grid;
  std::span<const Vec3f> bx = bgrid.sorted_points();
  const std::vector<float>& bvol = boundary.sorted_volume;
  const size_t cells = grid.occupied_cell_count();
  const size_t tasks = (cells + kCellsPerTask - 1) / kCellsPerTask;
  nb.tasks.resize(tasks);
  nb.counts.resize(2 * n);
  nb.boundary_grad.resize(n);
  const float eps = 1.0e-6f / h2;

  // One sweep per cell: gather the 27-cell block once (structure of arrays, padded for SIMD), then for
  // each particle of the cell compute all squared distances in a vectorisable loop and keep the
  // pairs within h. Pairs go to task-local buffers in particle order and are copied into place below.
  // Density (the SPH sum of [BK17] plus the boundary term of [AIA12]) and the DFSPH factor
  // alpha_i = 1 / (|sum_j V_j grad W_ij|^2 + sum_j |V_j grad W_ij|^2) (the factor of [BK17] divided by
  // rho_i, as our pressures are p / rho, see pressure.h) come out of the same sweep. Boundary
  // neighbours enter the first sum only: they do not move in response to particle i's pressure.
  parallel_for(tasks, 1, [&](size_t tb, size_t te) {
    BlockBuffer block;
    std::vector<float> d2;
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
        const float *bxs = block.x(), *bys = block.y(), *bzs = block.z();
        const uint32_t* index = block.sorted_index();
        for (uint32_t i = grid.cell_begin(c); i < grid.cell_begin(c + 1); ++i) {
          const Vec3f xi = p.x[i];
          const float px = xi.x(), py = xi.y(), pz = xi.z();
          const size_t hits = candidates_within(bxs, bys, bzs, m, px, py, pz, h2, d2.data(), hit.data());
          const size_t first = task.pairs.size();
          float w_sum = kernel.value_at_zero();
          Vec3f g_fluid = Vec3f::Zero();
          float g2_sum = 0.0f;
          for (size_t c_hit = 0; c_hit < hits; ++c_hit) {
            const size_t k = hit[c_hit];
            const uint32_t j = index[k];
            if (j == i) continue;
            const float r = std::sqrt(d2[k]);
            const FluidPair q{j, volume * kernel.grad_factor(r)};
            const Vec3f g = q.g(xi - p.x[j]);
            task.pairs.push_back(q);
            w_sum += kernel.value(r);
            g_fluid += g;
            g2_sum += g.squaredNorm();
          }
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
