#include "sim/grid/neighbour_grid.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_sort.h>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {

void NeighbourGrid::build(std::span<const Vec3f> points, float support_radius) {
  if (!(support_radius > 0.0f) || !std::isfinite(support_radius))
    fail("neighbour grid: support radius ", support_radius, " must be a finite number > 0");
  support_radius_ = support_radius;
  const size_t n = points.size();
  sorted_points_.resize(n);
  order_.resize(n);
  if (n == 0) {
    dims_ = {0, 0, 0};
    cell_start_.assign(1, 0);
    occupied_keys_.clear();
    return;
  }

  // Bounding box, then the dense cell layout with one empty cell of margin on every side.
  Aabb box;
  for (const Vec3f& p : points) box.extend(p);
  const Vec3d extent = (box.max - box.min).cast<double>();
  const double max_cells = std::max(4.0e6, 4.0 * double(n));
  double cell = support_radius;
  auto cells_needed = [&](double c) {
    return (std::floor(extent.x() / c) + 3) * (std::floor(extent.y() / c) + 3) * (std::floor(extent.z() / c) + 3);
  };
  while (cells_needed(cell) > max_cells) cell *= 1.25;
  cell_ = float(cell);
  origin_ = box.min - Vec3f::Constant(cell_);
  for (int a = 0; a < 3; ++a) dims_[a] = int(std::floor(extent[a] / cell)) + 3;

  // Sort (key, index) pairs packed in 64 bits: unique, so the parallel sort is deterministic.
  std::vector<uint64_t>& packed = packed_;
  packed.resize(n);
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) packed[i] = (uint64_t(key_of(points[i])) << 32) | uint32_t(i);
  });
  tbb::parallel_sort(packed.begin(), packed.end());

  const uint32_t keys = key_count();
  cell_start_.assign(size_t(keys) + 1, 0);
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      order_[i] = uint32_t(packed[i]);
      sorted_points_[i] = points[order_[i]];
    }
  });
  // cell_start[k] = number of points with key < k, filled by walking the sorted keys once.
  occupied_keys_.clear();
  uint32_t k = 0;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t key = uint32_t(packed[i] >> 32);
    if (i == 0 || key != uint32_t(packed[i - 1] >> 32)) occupied_keys_.push_back(key);
    while (k <= key) cell_start_[k++] = uint32_t(i);
  }
  while (k <= keys) cell_start_[k++] = uint32_t(n);
}

uint32_t NeighbourGrid::key_of(const Vec3f& p) const {
  if (sorted_points_.empty()) return kOutside;
  int c[3];
  for (int a = 0; a < 3; ++a) {
    const float f = std::floor((p[a] - origin_[a]) / cell_);
    if (!(f >= 0.0f) || f >= float(dims_[a])) return kOutside;  // also catches NaN
    c[a] = int(f);
  }
  return (uint32_t(c[2]) * uint32_t(dims_[1]) + uint32_t(c[1])) * uint32_t(dims_[0]) + uint32_t(c[0]);
}

// A batch without branches, built for AVX2 and baseline x86-64 and picked at load time: per point it
// is key_of's expression (so the same cell), 8 points at a time. One call per point took 4% of a
// 15M-particle diffuse frame's CPU time. A free function: clang 14 emits no load-time choice for a
// member function with target_clones defined out of its class.
__attribute__((target_clones("avx2", "default"))) void octant_keys_of(const float* xyz, size_t n, float cell,
                                                                      const float origin[3], const int dims[3],
                                                                      uint32_t* keys) {
  const float ox = origin[0], oy = origin[1], oz = origin[2];
  const float nx = float(dims[0]), ny = float(dims[1]), nz = float(dims[2]);
  const uint32_t row = uint32_t(dims[0]), layer = uint32_t(dims[0]) * uint32_t(dims[1]);
  for (size_t i = 0; i < n; ++i) {
    const float ux = (xyz[3 * i] - ox) / cell, uy = (xyz[3 * i + 1] - oy) / cell, uz = (xyz[3 * i + 2] - oz) / cell;
    const float fx = std::floor(ux), fy = std::floor(uy), fz = std::floor(uz);
    // !(f >= 0) also catches NaN; an outside point's cell is taken as 0 so the conversion stays defined.
    const bool inside = fx >= 0.0f && fx < nx && fy >= 0.0f && fy < ny && fz >= 0.0f && fz < nz;
    const uint32_t cx = uint32_t(int(inside ? fx : 0.0f)), cy = uint32_t(int(inside ? fy : 0.0f)),
                   cz = uint32_t(int(inside ? fz : 0.0f));
    const uint32_t octant = (ux - fx >= 0.5f ? 1u : 0u) | (uy - fy >= 0.5f ? 2u : 0u) | (uz - fz >= 0.5f ? 4u : 0u);
    const uint32_t key = (cz * layer + cy * row + cx) * 8 + octant;
    keys[i] = inside ? key : NeighbourGrid::kOutside;
  }
}

void NeighbourGrid::octant_keys(std::span<const Vec3f> points, std::span<uint32_t> keys) const {
  if (sorted_points_.empty()) {
    std::fill(keys.begin(), keys.end(), kOutside);
    return;
  }
  const float origin[3] = {origin_[0], origin_[1], origin_[2]};
  const int dims[3] = {int(dims_[0]), int(dims_[1]), int(dims_[2])};
  octant_keys_of(points.empty() ? nullptr : points[0].data(), points.size(), cell_, origin, dims, keys.data());
}

template <int reach>
std::array<NeighbourGrid::Range, (2 * reach + 1) * (2 * reach + 1)> NeighbourGrid::rows_around(uint32_t key) const {
  const uint32_t nx = uint32_t(dims_[0]), ny = uint32_t(dims_[1]), nz = uint32_t(dims_[2]);
  const uint32_t cx = key % nx, cy = (key / nx) % ny, cz = key / (nx * ny);
  const uint32_t x0 = cx >= uint32_t(reach) ? cx - reach : 0, x1 = std::min(cx + reach, nx - 1);
  std::array<Range, (2 * reach + 1) * (2 * reach + 1)> ranges;
  int r = 0;
  for (int dz = -reach; dz <= reach; ++dz)
    for (int dy = -reach; dy <= reach; ++dy) {
      const int64_t y = int64_t(cy) + dy, z = int64_t(cz) + dz;
      if (y < 0 || z < 0 || y >= ny || z >= nz) {
        ranges[r++] = {0, 0};
        continue;
      }
      const uint32_t row = (uint32_t(z) * ny + uint32_t(y)) * nx;
      ranges[r++] = {cell_start_[row + x0], cell_start_[row + x1 + 1]};
    }
  return ranges;
}
template std::array<NeighbourGrid::Range, 9> NeighbourGrid::rows_around<1>(uint32_t) const;
template std::array<NeighbourGrid::Range, 25> NeighbourGrid::rows_around<2>(uint32_t) const;

}  // namespace spume
