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

uint32_t NeighbourGrid::octant_key_of(const Vec3f& p) const {
  if (sorted_points_.empty()) return kOutside;
  int c[3];
  uint32_t octant = 0;
  for (int a = 0; a < 3; ++a) {
    // The same cell as key_of (same expression), then the half of it from the fractional part.
    const float u = (p[a] - origin_[a]) / cell_;
    const float f = std::floor(u);
    if (!(f >= 0.0f) || f >= float(dims_[a])) return kOutside;
    c[a] = int(f);
    octant |= (u - f >= 0.5f ? 1u : 0u) << a;
  }
  const uint32_t key = (uint32_t(c[2]) * uint32_t(dims_[1]) + uint32_t(c[1])) * uint32_t(dims_[0]) + uint32_t(c[0]);
  return key * 8 + octant;
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
