#include "sim/diffuse/fluid_sampling.h"

#include <algorithm>
#include <bit>

#include "sim/core/huge_pages.h"
#include "sim/core/parallel.h"
#include "sim/diffuse/poly6_sums.h"
#include "sim/grid/block_buffer.h"

namespace spume {
namespace {

// Smallest half-cell group for which the block is cut down to the group's reach first.
constexpr uint32_t kFilterFrom = 6;

}  // namespace

size_t FluidSamples::bytes() const {
  return held_bytes(neighbour_count) + held_bytes(fluid_velocity) + held_bytes(kernel_sum) + held_bytes(cell_order) +
         held_bytes(group_start) + sorter.bytes();
}

void sample_fluid(const NeighbourGrid& grid, std::span<const Vec3f> sorted_motion, std::span<const Vec3f> positions,
                  FluidSamples& out) {
  const size_t n = positions.size();
  resize_discarding_in_huge_pages(out.neighbour_count, n);
  resize_discarding_in_huge_pages(out.fluid_velocity, n);
  resize_discarding_in_huge_pages(out.kernel_sum, n);

  // Sort by half-cell (by cell on a grid too large for half-cell keys); particles away from all fluid
  // share the key one past the last and sort last.
  const bool halves = grid.key_count() <= NeighbourGrid::kMaxOctantKeys;
  const uint32_t outside = halves ? grid.key_count() * 8 : grid.key_count();
  std::vector<uint32_t>& keys = out.sorter.input_keys();
  resize_discarding_in_huge_pages(keys, n);
  parallel_for(n, 1 << 14, [&](size_t b, size_t e) {
    if (halves) grid.octant_keys(positions.subspan(b, e - b), std::span(keys).subspan(b, e - b));
    for (size_t i = b; i < e; ++i) {
      const uint32_t k = halves ? keys[i] : grid.key_of(positions[i]);
      keys[i] = k == NeighbourGrid::kOutside ? outside : k;
    }
  });
  out.sorter.sort_input_keys(std::bit_width(outside));
  const std::vector<uint32_t>& order = out.sorter.order();
  const std::vector<uint32_t>& sorted = out.sorter.sorted_keys();

  // Groups: runs of equal key in sorted order, fluid-free particles excluded.
  const size_t inside_end = size_t(std::lower_bound(sorted.begin(), sorted.end(), outside) - sorted.begin());
  // Shrunk to the group count below, so without headroom every frame with a few more particles than
  // the last would reallocate it whole (15M particles: 60 MB of fresh memory a frame).
  if (out.group_start.capacity() < inside_end + 1) out.group_start.reserve(inside_end + 1 + inside_end / 8);
  out.group_start.resize(inside_end + 1);
  const size_t groups = parallel_select(
      inside_end, [&](size_t s) { return s == 0 || sorted[s] != sorted[s - 1]; },
      [&](size_t s, size_t k) { out.group_start[k] = uint32_t(s); });
  out.group_start.resize(groups + 1);
  out.group_start[groups] = uint32_t(inside_end);

  parallel_for(n - inside_end, 1 << 14, [&](size_t b, size_t e) {
    for (size_t s = inside_end + b; s < inside_end + e; ++s) {
      const uint32_t i = order[s];
      out.neighbour_count[i] = 0.0f, out.kernel_sum[i] = 0.0f, out.fluid_velocity[i] = Vec3f::Zero();
    }
  });

  const float h = grid.support_radius(), inv_h2 = 1.0f / (h * h);
  // Slightly more than h, so that rounding cannot drop a point the kernel would count.
  const Vec3f reach = Vec3f::Constant(1.001f * h);
  parallel_for(groups, 16, [&](size_t gb, size_t ge) {
    BlockBuffer block, near;
    uint32_t block_cell = NeighbourGrid::kOutside;
    for (size_t g = gb; g < ge; ++g) {
      const uint32_t first = out.group_start[g], last = out.group_start[g + 1];
      const uint32_t cell = halves ? sorted[first] >> 3 : sorted[first];
      if (cell != block_cell) block.gather(grid, cell, {sorted_motion}), block_cell = cell;
      const BlockBuffer* scan = &block;
      // Filtering costs about one block scan; it pays off for groups of several particles.
      if (halves && last - first >= kFilterFrom) {
        Aabb box;
        for (uint32_t s = first; s < last; ++s) box.extend(positions[order[s]]);
        box.min -= reach, box.max += reach;
        near.gather_within(block, box);
        scan = &near;
      }
      poly6_sums_for(*scan, std::span(order).subspan(first, last - first), positions.data(), inv_h2, 1.0f,
                     out.neighbour_count.data(), out.kernel_sum.data(), out.fluid_velocity.data());
    }
  });
  out.cell_order.swap(out.sorter.order());  // the sorter reuses the old buffer next time
}

}  // namespace spume
