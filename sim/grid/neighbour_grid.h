#pragma once
// Cell-sorted uniform grid for fixed-radius neighbour queries (one implementation for the whole
// project: normals, potentials, classification, advection and the fluid solver).
//
// Points are sorted by a dense cell key (z, then y, then x) over their bounding box grown by one cell.
// Because cells of one x-row are contiguous in that order, the 3x3x3 block around a cell is 9
// contiguous ranges of the sorted points: a query costs 18 table reads and no hashing. Cells are at
// least the support radius h, so all neighbours within h lie in the block.
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "sim/core/vec.h"

namespace spume {

class NeighbourGrid {
 public:
  static constexpr uint32_t kOutside = UINT32_MAX;  // key of a point outside the grid's box
  using Range = std::pair<uint32_t, uint32_t>;      // [begin, end) into the sorted points

  // Sorts `points` into cells of size >= support_radius (larger only if the box would need more than
  // max(4M, 4n) cells: the grid stays correct, just coarser). Deterministic for any thread count.
  void build(std::span<const Vec3f> points, float support_radius);

  float support_radius() const { return support_radius_; }
  float cell_size() const { return cell_; }
  size_t size() const { return sorted_points_.size(); }

  // Points in cell order, and the original index of each.
  std::span<const Vec3f> sorted_points() const { return sorted_points_; }
  std::span<const uint32_t> sorted_to_original() const { return order_; }

  // Dense key of the cell holding p, or kOutside when p is farther than one cell from every point
  // (then p has no neighbour within h).
  uint32_t key_of(const Vec3f& p) const;
  uint32_t key_count() const { return uint32_t(dims_[0]) * dims_[1] * dims_[2]; }
  // keys[i] = key_of(points[i]) * 8 plus which half of its cell the point lies in along x (bit 0),
  // y (bit 1) and z (bit 2); kOutside as key_of. Sorting by it groups points by half-cell. Needs
  // key_count() <= kMaxOctantKeys; keys.size() == points.size().
  void octant_keys(std::span<const Vec3f> points, std::span<uint32_t> keys) const;
  static constexpr uint32_t kMaxOctantKeys = (1u << 29) - 1;

  // Occupied cells in sorted order: cell c holds sorted points [cell_begin(c), cell_begin(c + 1)).
  size_t occupied_cell_count() const { return occupied_keys_.size(); }
  uint32_t occupied_key(size_t c) const { return occupied_keys_[c]; }
  uint32_t cell_begin(size_t c) const { return c < occupied_keys_.size() ? cell_start_[occupied_keys_[c]] : uint32_t(size()); }

  // The 9 row ranges covering the 3x3x3 cells around `key` (which must not be kOutside).
  std::array<Range, 9> block_ranges(uint32_t key) const { return rows_around<1>(key); }
  // The 25 row ranges covering the 5x5x5 cells around `key`: every point within two support radii.
  std::array<Range, 25> wide_block_ranges(uint32_t key) const { return rows_around<2>(key); }

  // fn(sorted_index, squared_distance) for every point within `radius` (<= support radius) of p.
  template <typename Fn>
  void for_each_neighbour(const Vec3f& p, float radius, Fn&& fn) const {
    const uint32_t key = key_of(p);
    if (key != kOutside) visit_within(block_ranges(key), p, radius, fn);
  }
  // The same for a radius up to two support radii (the wave-crest sum, MODEL.md §8.10).
  template <typename Fn>
  void for_each_neighbour_wide(const Vec3f& p, float radius, Fn&& fn) const {
    const uint32_t key = key_of(p);
    if (key != kOutside) visit_within(wide_block_ranges(key), p, radius, fn);
  }

 private:
  template <typename Ranges, typename Fn>
  void visit_within(const Ranges& ranges, const Vec3f& p, float radius, Fn& fn) const {
    const float r2 = radius * radius;
    for (const Range& r : ranges)
      for (uint32_t j = r.first; j < r.second; ++j) {
        const float d2 = (sorted_points_[j] - p).squaredNorm();
        if (d2 <= r2) fn(j, d2);
      }
  }
  // Row ranges of the (2 reach + 1)^3 cells around `key`, clipped to the grid.
  template <int reach>
  std::array<Range, (2 * reach + 1) * (2 * reach + 1)> rows_around(uint32_t key) const;

  float support_radius_ = 0.0f;
  float cell_ = 1.0f;
  Vec3f origin_ = Vec3f::Zero();
  std::array<int, 3> dims_ = {0, 0, 0};
  std::vector<uint32_t> cell_start_;  // key_count() + 1 entries: first sorted index of each cell
  std::vector<uint32_t> occupied_keys_;
  std::vector<Vec3f> sorted_points_;
  std::vector<uint32_t> order_;
  std::vector<uint64_t> packed_;  // build()'s (key, index) pairs, kept so rebuilding reuses the memory
};

}  // namespace spume
