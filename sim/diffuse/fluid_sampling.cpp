#include "fluid_sampling.h"

#include <algorithm>
#include <bit>

#include "core/parallel.h"
#include "grid/block_buffer.h"
#include "grid/radix_sort.h"

namespace spume {

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
    BlockBuffer block;
    for (size_t g = gb; g < ge; ++g) {
      const uint32_t first = group_start[g], last = group_start[g + 1];
      block.gather(grid, keys[out.cell_order[first]], {sorted_motion});
      const size_t m = block.size();
      const float *bx = block.x(), *by = block.y(), *bz = block.z();
      const float *bvx = block.attribute(0, 0), *bvy = block.attribute(0, 1), *bvz = block.attribute(0, 2);
      for (uint32_t s = first; s < last; ++s) {
        const uint32_t i = out.cell_order[s];
        const float px = positions[i].x(), py = positions[i].y(), pz = positions[i].z();
        float count[kLanes] = {}, wsum[kLanes] = {}, wx[kLanes] = {}, wy[kLanes] = {}, wz[kLanes] = {};
        for (size_t j = 0; j < m; j += kLanes)
          for (size_t l = 0; l < kLanes; ++l) {
            const float dx = bx[j + l] - px, dy = by[j + l] - py, dz = bz[j + l] - pz;
            const float q2 = std::min((dx * dx + dy * dy + dz * dz) * inv_h2, 4.0f);
            const float t = std::max(1.0f - q2, 0.0f);
            const float w = t * t * t;  // poly6 shape (1 - r^2/h^2)^3; its constant cancels in the ratio
            count[l] += q2 <= 1.0f ? 1.0f : 0.0f;
            wsum[l] += w;
            wx[l] += w * bvx[j + l], wy[l] += w * bvy[j + l], wz[l] += w * bvz[j + l];
          }
        const float total = lane_sum(wsum);
        out.neighbour_count[i] = lane_sum(count);
        out.kernel_sum[i] = total;
        if (total > 0.0f) out.fluid_velocity[i] = Vec3f(lane_sum(wx), lane_sum(wy), lane_sum(wz)) / total;
      }
    }
  });
}

}  // namespace spume
