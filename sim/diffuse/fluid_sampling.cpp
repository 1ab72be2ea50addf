#include "fluid_sampling.h"

#include <algorithm>
#include <bit>

#include "core/parallel.h"
#include "grid/radix_sort.h"

namespace spume {
namespace {

// Fluid particles of one 3x3x3 block, structure of arrays for a tight inner loop.
struct CandidateBuffer {
  std::vector<float> x, y, z, vx, vy, vz;
  void gather(const NeighbourGrid& grid, std::span<const Vec3f> sorted_motion, uint32_t key) {
    x.clear(), y.clear(), z.clear(), vx.clear(), vy.clear(), vz.clear();
    const auto points = grid.sorted_points();
    for (const auto& [b, e] : grid.block_ranges(key))
      for (uint32_t j = b; j < e; ++j) {
        x.push_back(points[j].x()), y.push_back(points[j].y()), z.push_back(points[j].z());
        vx.push_back(sorted_motion[j].x()), vy.push_back(sorted_motion[j].y()), vz.push_back(sorted_motion[j].z());
      }
  }
};

}  // namespace

void sample_fluid(const NeighbourGrid& grid, std::span<const Vec3f> sorted_motion, std::span<const Vec3f> positions,
                  FluidSamples& out) {
  const size_t n = positions.size();
  out.neighbour_count.assign(n, 0.0f);
  out.fluid_velocity.assign(n, Vec3f::Zero());
  out.kernel_sum.assign(n, 0.0f);

  // Sort by cell; particles away from all fluid share the key one past the last cell and sort last.
  const uint32_t outside = grid.key_count();
  std::vector<uint32_t> keys(n);
  parallel_for(n, 1 << 14, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const uint32_t k = grid.key_of(positions[i]);
      keys[i] = k == NeighbourGrid::kOutside ? outside : k;
    }
  });
  out.cell_order = radix_sort_indices(keys, std::bit_width(outside));

  // Group boundaries: runs of equal key in cell order, fluid-free particles excluded.
  std::vector<uint32_t> group_start;
  for (size_t s = 0; s < n; ++s) {
    const uint32_t k = keys[out.cell_order[s]];
    if (k == outside) break;
    if (s == 0 || k != keys[out.cell_order[s - 1]]) group_start.push_back(uint32_t(s));
  }
  size_t inside_end = group_start.empty() ? 0 : group_start.back();
  while (inside_end < n && keys[out.cell_order[inside_end]] != outside) ++inside_end;
  group_start.push_back(uint32_t(inside_end));

  const float h = grid.support_radius(), inv_h2 = 1.0f / (h * h);
  parallel_for(group_start.size() - 1, 8, [&](size_t gb, size_t ge) {
    CandidateBuffer buffer;
    for (size_t g = gb; g < ge; ++g) {
      const uint32_t first = group_start[g], last = group_start[g + 1];
      buffer.gather(grid, sorted_motion, keys[out.cell_order[first]]);
      const size_t m = buffer.x.size();
      const float *bx = buffer.x.data(), *by = buffer.y.data(), *bz = buffer.z.data();
      const float *bvx = buffer.vx.data(), *bvy = buffer.vy.data(), *bvz = buffer.vz.data();
      for (uint32_t s = first; s < last; ++s) {
        const uint32_t i = out.cell_order[s];
        const float px = positions[i].x(), py = positions[i].y(), pz = positions[i].z();
        // Branch-free so the compiler vectorises it: candidates beyond h contribute zero.
        float count = 0.0f, wsum = 0.0f, wx = 0.0f, wy = 0.0f, wz = 0.0f;
        for (size_t j = 0; j < m; ++j) {
          const float dx = bx[j] - px, dy = by[j] - py, dz = bz[j] - pz;
          const float q2 = (dx * dx + dy * dy + dz * dz) * inv_h2;
          const float inside = q2 <= 1.0f ? 1.0f : 0.0f;
          const float t = std::max(1.0f - q2, 0.0f);
          const float w = t * t * t;  // poly6 shape (1 - r^2/h^2)^3; its constant cancels in the ratio
          count += inside;
          wsum += w;
          wx += w * bvx[j], wy += w * bvy[j], wz += w * bvz[j];
        }
        out.neighbour_count[i] = count;
        out.kernel_sum[i] = wsum;
        if (wsum > 0.0f) out.fluid_velocity[i] = Vec3f(wx, wy, wz) / wsum;
      }
    }
  });
}

}  // namespace spume
