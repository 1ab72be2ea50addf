#include "sim/fluid/boundary_pressure.h"

#include <algorithm>

#include "sim/core/parallel.h"

namespace spume::fluid {

void WallPressure::build(const Neighbourhoods& nb, const Boundary& boundary, const CubicSpline& kernel,
                         const Particles& p, const Vec3f& gravity) {
  const size_t n = p.size(), nbound = boundary.size();
  std::span<const Vec3f> bx = boundary.grid.sorted_points();
  // Transpose the fluid -> boundary pairs by counting, in fluid order: each sample's fluid neighbours
  // come out ascending, whatever the thread count.
  next.assign(nbound, 0);
  for (const Pair& q : nb.boundary_pairs) ++next[q.j];
  sample.clear();
  offset.assign(1, 0);
  for (uint32_t b = 0; b < nbound; ++b)
    if (next[b]) {
      const uint32_t count = next[b];
      next[b] = offset.back();
      sample.push_back(b);
      offset.push_back(offset.back() + count);
    }
  fluid.resize(offset.back());
  weight.resize(offset.back());
  for (size_t i = 0; i < n; ++i)
    for (uint32_t e = nb.boundary_offset[i]; e < nb.boundary_offset[i + 1]; ++e) {
      const uint32_t b = nb.boundary_pairs[e].j;
      const uint32_t at = next[b]++;
      fluid[at] = uint32_t(i);
      weight[at] = kernel.value((p.x[i] - bx[b]).norm());
    }
  rise.resize(sample.size());
  parallel_for(sample.size(), 1024, [&](size_t lo, size_t hi) {
    for (size_t s = lo; s < hi; ++s) {
      float sum = 0.0f;
      Vec3f arm = Vec3f::Zero();
      const Vec3f xb = bx[sample[s]];
      for (uint32_t e = offset[s]; e < offset[s + 1]; ++e) sum += weight[e];
      const float inv = sum > 0.0f ? 1.0f / sum : 0.0f;
      for (uint32_t e = offset[s]; e < offset[s + 1]; ++e) {
        weight[e] *= inv;
        arm += weight[e] * (xb - p.x[fluid[e]]);
      }
      rise[s] = gravity.dot(arm);
    }
  });
  k.assign(nbound, 0.0f);
  total.assign(nbound, 0.0f);
}

void WallPressure::extrapolate(const std::vector<float>& fluid_k, float rise_scale) {
  parallel_for(sample.size(), 1024, [&](size_t lo, size_t hi) {
    for (size_t s = lo; s < hi; ++s) {
      float kb = rise_scale * rise[s];
      for (uint32_t e = offset[s]; e < offset[s + 1]; ++e) kb += weight[e] * fluid_k[fluid[e]];
      // The wall never pulls. The fluid's increments are >= 0, so only the first can come out
      // negative, from the rise of a wall above the water; that part of the rise is dropped.
      const uint32_t b = sample[s];
      k[b] = std::max(kb, 0.0f);
      total[b] += k[b];
    }
  });
}

}  // namespace spume::fluid
