#pragma once
// Where no solid is near, over the whole scene at once: a bit a cell on a grid over the tanks' interior,
// set where a ball of radius `reach` around any point of the cell meets no solid and stays inside every
// tank's walls. The diffuse model's per-particle solid tests (SolidSet::push_out, stop_at_tank_walls,
// solid_coverage_bounds, solid_coverage within `reach`) change nothing for such a point, so they are
// skipped there; at 15M particles they otherwise cost a fifth of a frame, almost all of it on particles
// far from every solid.
//
// Conservative by construction: a cell is clear only when the exact tests, with their own rounding, say
// so for every point of it widened by a slack (2% of a cell, plus ulps of the coordinates) that also
// covers a point rounded into the neighbouring cell. Outside the grid a point is clear only when the
// scene has no tank (then the grid covers every solid within reach).
#include <array>
#include <cstdint>
#include <vector>

#include "sim/core/vec.h"
#include "sim/geometry/solids.h"

namespace spume {

class SolidClearance {
 public:
  SolidClearance() = default;  // built for nothing: clear() is always false
  SolidClearance(const SolidSet& solids, float reach);

  // True only if the ball of radius `reach` (as built) around p meets no solid and lies inside every
  // tank's walls.
  bool clear(const Vec3f& p) const {
    const float x = (p.x() - origin_.x()) * per_cell_, y = (p.y() - origin_.y()) * per_cell_,
                z = (p.z() - origin_.z()) * per_cell_;
    if (!(x >= 0.0f && y >= 0.0f && z >= 0.0f && x < dims_[0] && y < dims_[1] && z < dims_[2]))
      return outside_clear_ && p.allFinite();
    const size_t cell = size_t(x) + size_t(dims_[0]) * (size_t(y) + size_t(dims_[1]) * size_t(z));
    return (bits_[cell >> 6] >> (cell & 63)) & 1;
  }

  bool built() const { return built_; }
  float cell_size() const { return per_cell_ > 0.0f ? 1.0f / per_cell_ : 0.0f; }
  size_t clear_cells() const;  // how many cells are clear (for tests and reports)

 private:
  void set(size_t cell, bool clear);

  Vec3f origin_ = Vec3f::Zero();
  float per_cell_ = 0.0f;
  std::array<float, 3> dims_{0.0f, 0.0f, 0.0f};  // cells along each axis (floats: compared with x, y, z)
  std::vector<uint64_t> bits_;
  bool outside_clear_ = false, built_ = false;
};

// At most this many cells: the grid's bits fit in 512 KiB, near the cores' caches; a scene larger than
// that at a cell of `reach` gets coarser cells.
constexpr size_t kClearanceMaxCells = size_t(1) << 22;

}  // namespace spume
