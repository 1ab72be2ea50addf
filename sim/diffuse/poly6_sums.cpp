#include "sim/diffuse/poly6_sums.h"

#include <algorithm>

namespace spume {

// Built twice,
// for AVX2 and for baseline x86-64, picked at load time: the lane loop is the same IEEE arithmetic
// either way (no FMA: contraction is off), so the results are too.
__attribute__((target_clones("avx2", "default"))) void poly6_sums(const BlockBuffer& block, const Vec3f& p, float inv_h2,
                                                                   float count_q2, float& count_out,
                                                                   float& kernel_out, Vec3f& velocity_out) {
  const size_t m = block.size();
  const float *bx = block.x(), *by = block.y(), *bz = block.z();
  const float *bvx = block.attribute(0, 0), *bvy = block.attribute(0, 1), *bvz = block.attribute(0, 2);
  const float px = p.x(), py = p.y(), pz = p.z();
  float count[kLanes] = {}, wsum[kLanes] = {}, wx[kLanes] = {}, wy[kLanes] = {}, wz[kLanes] = {};
  for (size_t j = 0; j < m; j += kLanes)
    for (size_t l = 0; l < kLanes; ++l) {
      const float dx = bx[j + l] - px, dy = by[j + l] - py, dz = bz[j + l] - pz;
      const float q2 = std::min((dx * dx + dy * dy + dz * dz) * inv_h2, 4.0f);
      const float t = std::max(1.0f - q2, 0.0f);
      const float w = t * t * t;  // poly6 shape (1 - r^2/h^2)^3; its constant cancels in the ratio
      count[l] += q2 <= count_q2 ? 1.0f : 0.0f;
      wsum[l] += w;
      wx[l] += w * bvx[j + l], wy[l] += w * bvy[j + l], wz[l] += w * bvz[j + l];
    }
  const float total = lane_sum(wsum);
  count_out = lane_sum(count);
  kernel_out = total;
  velocity_out = total > 0.0f ? Vec3f(Vec3f(lane_sum(wx), lane_sum(wy), lane_sum(wz)) / total) : Vec3f::Zero();
}

}  // namespace spume
