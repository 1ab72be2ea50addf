#pragma once
// delta(x) of Eq. 9 for the march integrator: is x within r of a particle of one type? Centres are
// counting-sorted into a uniform grid with cells of at least 2r, so a sphere containing x has its
// centre in one of the 2x2x2 cells nearest x (per axis: x's cell and the neighbour on x's side).
#include <cstdint>
#include <vector>

#include "sim/core/frames.h"

namespace spume {

class PointGrid {
 public:
  PointGrid() = default;
  // The particles of `type` in `frame`, spheres of radius r (m, > 0).
  PointGrid(DiffuseView frame, DiffuseType type, float radius);

  bool empty() const { return points_.empty(); }
  bool covers(const Vec3d& x) const;
  size_t memory_bytes() const { return points_.size() * sizeof(Vec3f) + start_.size() * sizeof(uint32_t); }

 private:
  double r2_ = 0.0, cell_ = 1.0, inv_cell_ = 1.0;
  Vec3d lo_ = Vec3d::Zero();
  int n_[3] = {1, 1, 1};
  std::vector<uint32_t> start_;  // cells + 1 offsets into points_
  std::vector<Vec3f> points_;    // centres in cell order
};

}  // namespace spume
