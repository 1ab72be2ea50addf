#include "render/surface/outward_normals.h"

#include <algorithm>
#include <cmath>

namespace spume {

void OutwardNormals::build(std::span<const Vec3f> particles, const Vec3f& lo, const Vec3f& extent, float support) {
  h_ = support, lo_ = lo;
  size_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    dims_[a] = std::max(1, int(std::ceil(extent[a] / support)));
    cells *= size_t(dims_[a]);
  }
  // Counting sort by cell; stable, so the order within a cell is the gather order.
  cell_of_.resize(particles.size());
  start_.assign(cells + 1, 0);
  for (size_t i = 0; i < particles.size(); ++i) {
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(int((particles[i][a] - lo[a]) / support), 0, dims_[a] - 1);
    cell_of_[i] = uint32_t((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
    ++start_[cell_of_[i] + 1];
  }
  for (size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  sorted_.resize(particles.size());
  std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < particles.size(); ++i) sorted_[fill[cell_of_[i]]++] = particles[i];
}

Vec3f OutwardNormals::at(const Vec3f& x, const Vec3f& fallback) const {
  int c[3];
  for (int a = 0; a < 3; ++a) c[a] = std::clamp(int(std::floor((x[a] - lo_[a]) / h_)), 0, dims_[a] - 1);
  const float inv_h2 = 1.0f / (h_ * h_);
  Vec3f g = Vec3f::Zero();
  for (int z = std::max(0, c[2] - 1); z <= std::min(dims_[2] - 1, c[2] + 1); ++z)
    for (int y = std::max(0, c[1] - 1); y <= std::min(dims_[1] - 1, c[1] + 1); ++y) {
      // The x-neighbours of a row are contiguous: one range.
      const int row = (z * dims_[1] + y) * dims_[0];
      const uint32_t b = start_[size_t(row + std::max(0, c[0] - 1))];
      const uint32_t e = start_[size_t(row + std::min(dims_[0] - 1, c[0] + 1) + 1)];
      for (uint32_t j = b; j < e; ++j) {
        const Vec3f d = x - sorted_[j];
        const float q = 1.0f - d.squaredNorm() * inv_h2;
        if (q > 0.0f) g += (q * q) * d;
      }
    }
  const float len = g.norm();
  return len > 0.0f ? Vec3f(g / len) : fallback;
}

}  // namespace spume
