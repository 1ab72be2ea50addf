#include "render/volume/point_grid.h"

#include <algorithm>
#include <cmath>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {

PointGrid::PointGrid(DiffuseView frame, DiffuseType type, float radius) {
  std::vector<uint32_t> idx;
  Aabb box;
  for (size_t i = 0; i < frame.size(); ++i)
    if (frame.types[i] == type) idx.push_back(uint32_t(i)), box.extend(frame.positions[i]);
  if (idx.empty()) return;
  r2_ = double(radius) * double(radius);
  lo_ = box.min.cast<double>();
  const Vec3d extent = (box.max - box.min).cast<double>();
  // Cells of 2r, grown when that would need more than max(2N, 2^16) cells (sparse spray over a
  // large scene): memory stays O(N) and the 2x2x2 rule still holds because cells only grow.
  const double max_cells = std::max(2.0 * double(idx.size()), 65536.0);
  cell_ = 2.0 * double(radius);
  auto cells_for = [&](double c) {
    return (std::floor(extent.x() / c) + 1) * (std::floor(extent.y() / c) + 1) * (std::floor(extent.z() / c) + 1);
  };
  while (cells_for(cell_) > max_cells) cell_ *= 1.25;
  inv_cell_ = 1.0 / cell_;
  for (int a = 0; a < 3; ++a) n_[a] = int(std::floor(extent[a] / cell_)) + 1;
  const size_t cells = size_t(n_[0]) * size_t(n_[1]) * size_t(n_[2]);

  std::vector<uint32_t> cell_of(idx.size());
  parallel_for(idx.size(), 1 << 14, [&](size_t b, size_t e) {
    for (size_t j = b; j < e; ++j) {
      const Vec3d q = (frame.positions[idx[j]].cast<double>() - lo_) * inv_cell_;
      size_t c = 0;
      for (int a = 2; a >= 0; --a) c = c * size_t(n_[a]) + size_t(std::clamp(int(q[a]), 0, n_[a] - 1));
      cell_of[j] = uint32_t(c);
    }
  });
  // Serial counting sort: exact and deterministic; march is the slow reference integrator anyway.
  start_.assign(cells + 1, 0);
  for (uint32_t c : cell_of) ++start_[c + 1];
  for (size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  points_.resize(idx.size());
  std::vector<uint32_t> cursor(start_.begin(), start_.end() - 1);
  for (size_t j = 0; j < idx.size(); ++j) points_[cursor[cell_of[j]]++] = frame.positions[idx[j]];
}

bool PointGrid::covers(const Vec3d& x) const {
  if (points_.empty()) return false;
  int c[3][2];
  int m[3];
  for (int a = 0; a < 3; ++a) {
    const double q = (x[a] - lo_[a]) * inv_cell_;
    if (q < -0.5 || q > double(n_[a]) + 0.5) return false;  // farther than r <= cell/2 from every cell
    // q >= -0.5 here, so truncation equals floor after the clamp (and avoids a libm call).
    const int i = std::clamp(int(q), 0, n_[a] - 1);
    const int j = q - double(i) < 0.5 ? i - 1 : i + 1;
    c[a][0] = i;
    m[a] = 1;
    if (j >= 0 && j < n_[a]) c[a][1] = j, m[a] = 2;
  }
  // x is the fastest axis, so the one or two x-cells of each (y, z) pair are one contiguous range.
  const size_t x_lo = size_t(m[0] == 2 ? std::min(c[0][0], c[0][1]) : c[0][0]);
  const size_t x_hi = size_t(m[0] == 2 ? std::max(c[0][0], c[0][1]) : c[0][0]);
  for (int iz = 0; iz < m[2]; ++iz)
    for (int iy = 0; iy < m[1]; ++iy) {
      const size_t row = (size_t(c[2][iz]) * size_t(n_[1]) + size_t(c[1][iy])) * size_t(n_[0]);
      for (uint32_t p = start_[row + x_lo], e = start_[row + x_hi + 1]; p < e; ++p)
        if ((points_[p].cast<double>() - x).squaredNorm() < r2_) return true;
    }
  return false;
}

}  // namespace spume
