#pragma once
// Vertex normals from the colour field's analytic gradient: n = -grad c / |grad c|, with
//   -grad c(x) proportional to sum_j (1 - |x - x_j|^2 / h^2)^2 (x - x_j)   over |x - x_j| < h.
// The particles near one brick are binned into cells of side h so each vertex visits only the 27
// cells around it (about 8x fewer particles than the brick's whole neighbourhood).
#include <span>
#include <vector>

#include "sim/core/vec.h"

namespace spume {

class OutwardNormals {
 public:
  // Bins `particles` (all within the box [lo, lo + extent]) for queries with support h (m).
  void build(std::span<const Vec3f> particles, const Vec3f& lo, const Vec3f& extent, float support);
  // Unit outward normal at x; `fallback` when the gradient vanishes (no particle within h).
  Vec3f at(const Vec3f& x, const Vec3f& fallback) const;

 private:
  float h_ = 1.0f;
  Vec3f lo_ = Vec3f::Zero();
  int dims_[3] = {0, 0, 0};
  std::vector<uint32_t> start_;  // dims product + 1 offsets into sorted_
  std::vector<Vec3f> sorted_;
  std::vector<uint32_t> cell_of_;
};

}  // namespace spume
