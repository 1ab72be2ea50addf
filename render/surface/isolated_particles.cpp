#include "render/surface/isolated_particles.h"

#include <numeric>

#include "sim/core/parallel.h"
#include "render/surface/sparse_bins.h"

namespace spume {

std::vector<uint32_t> connected_particles(std::span<const Vec3f> points, float support, int min_neighbours) {
  std::vector<uint32_t> kept;
  if (min_neighbours <= 0 || points.empty()) {
    kept.resize(points.size());
    std::iota(kept.begin(), kept.end(), 0u);
    return kept;
  }
  Aabb box;
  for (const Vec3f& p : points) box.extend(p);
  SparseBins bins;
  // Cells of side h: all neighbours closer than h lie in the 27 cells around a point's cell.
  bins.build(points, box.min - Vec3f::Constant(2 * support), support);

  const float h2 = support * support;
  std::vector<uint8_t> keep(points.size(), 0);
  parallel_for(bins.cell_count(), 16, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      // Own cell first: in a fluid body it alone usually holds enough neighbours, so the 26 cells
      // around are looked up only when a particle needs them (once per cell).
      std::span<const Vec3f> ranges[27];
      int nr = 1;
      bool looked_up = false;
      ranges[0] = bins.points(c);
      const std::array<int, 3> xyz = SparseBins::unpack(bins.key(c));
      const int x = xyz[0], y = xyz[1], z = xyz[2];
      auto look_up = [&] {
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              if (dx == 0 && dy == 0 && dz == 0) continue;
              const int64_t o = bins.find(x + dx, y + dy, z + dz);
              if (o != SparseBins::kMissing) ranges[nr++] = bins.points(size_t(o));
            }
        looked_up = true;
      };
      const auto own = bins.points(c);
      const auto own_index = bins.indices(c);
      for (size_t i = 0; i < own.size(); ++i) {
        int count = -1;  // the point itself is found at distance 0
        for (int r = 0; count < min_neighbours; ++r) {
          if (r == nr) {
            if (looked_up) break;
            look_up();
            if (r == nr) break;
          }
          for (const Vec3f& q : ranges[r])
            if ((q - own[i]).squaredNorm() < h2 && ++count >= min_neighbours) break;
        }
        keep[own_index[i]] = count >= min_neighbours;
      }
    }
  });
  for (uint32_t i = 0; i < keep.size(); ++i)
    if (keep[i]) kept.push_back(i);
  return kept;
}

}  // namespace spume
