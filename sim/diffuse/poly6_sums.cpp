#include "sim/diffuse/poly6_sums.h"

#include <algorithm>

#include "sim/core/target_clones.h"

namespace spume {

namespace {

// The lane loop, for P points at once over one block: each block point is loaded once for all P, and
// every point's sums are the same additions in the same order as alone. Inlined into the entry points
// below, which are built for several instruction sets, picked at load time: the lane loop is the same
// IEEE arithmetic on each (no FMA: contraction is off), so the results are too.
template <size_t P>
__attribute__((always_inline)) inline void sums_at(const BlockBuffer& block, const Vec3f* const (&p)[P], float inv_h2,
                                                   float count_q2, float* const (&count_out)[P],
                                                   float* const (&kernel_out)[P], Vec3f* const (&velocity_out)[P]) {
  const size_t m = block.size();
  const float *bx = block.x(), *by = block.y(), *bz = block.z();
  const float *bvx = block.attribute(0, 0), *bvy = block.attribute(0, 1), *bvz = block.attribute(0, 2);
  float px[P], py[P], pz[P];
  for (size_t k = 0; k < P; ++k) px[k] = p[k]->x(), py[k] = p[k]->y(), pz[k] = p[k]->z();
  float count[P][kLanes] = {}, wsum[P][kLanes] = {}, wx[P][kLanes] = {}, wy[P][kLanes] = {}, wz[P][kLanes] = {};
  for (size_t j = 0; j < m; j += kLanes)
    for (size_t k = 0; k < P; ++k)
      for (size_t l = 0; l < kLanes; ++l) {
        const float dx = bx[j + l] - px[k], dy = by[j + l] - py[k], dz = bz[j + l] - pz[k];
        const float q2 = std::min((dx * dx + dy * dy + dz * dz) * inv_h2, 4.0f);
        const float t = std::max(1.0f - q2, 0.0f);
        const float w = t * t * t;  // poly6 shape (1 - r^2/h^2)^3; its constant cancels in the ratio
        count[k][l] += q2 <= count_q2 ? 1.0f : 0.0f;
        wsum[k][l] += w;
        wx[k][l] += w * bvx[j + l], wy[k][l] += w * bvy[j + l], wz[k][l] += w * bvz[j + l];
      }
  for (size_t k = 0; k < P; ++k) {
    const float total = lane_sum(wsum[k]);
    *count_out[k] = lane_sum(count[k]);
    *kernel_out[k] = total;
    *velocity_out[k] =
        total > 0.0f ? Vec3f(Vec3f(lane_sum(wx[k]), lane_sum(wy[k]), lane_sum(wz[k])) / total) : Vec3f::Zero();
  }
}

// Points points[0..P) of the group, each into its own slot of the outputs.
template <size_t P>
__attribute__((always_inline)) inline void sums_of(const BlockBuffer& block, const uint32_t* points,
                                                   const Vec3f* positions, float inv_h2, float count_q2,
                                                   float* count_out, float* kernel_out, Vec3f* velocity_out) {
  const Vec3f* at[P];
  float *counts[P], *kernels[P];
  Vec3f* velocities[P];
  for (size_t k = 0; k < P; ++k) {
    const uint32_t i = points[k];
    at[k] = &positions[i], counts[k] = &count_out[i], kernels[k] = &kernel_out[i], velocities[k] = &velocity_out[i];
  }
  sums_at<P>(block, at, inv_h2, count_q2, counts, kernels, velocities);
}

}  // namespace

// Built three times, picked at load time (core/target_clones.h): for AVX-512 (x86-64-v4; on a 15M
// lighthouse frame the classification took 10% less time than with the AVX2 build of the same loop),
// AVX2 and baseline x86-64.
SPUME_CLONES_FOR_AVX512_AND_AVX2 void poly6_sums(
    const BlockBuffer& block, const Vec3f& p, float inv_h2, float count_q2, float& count_out, float& kernel_out,
    Vec3f& velocity_out) {
  const uint32_t only = 0;
  sums_of<1>(block, &only, &p, inv_h2, count_q2, &count_out, &kernel_out, &velocity_out);
}

SPUME_CLONES_FOR_AVX512_AND_AVX2 void poly6_sums_for(
    const BlockBuffer& block, std::span<const uint32_t> points, const Vec3f* positions, float inv_h2, float count_q2,
    float* count_out, float* kernel_out, Vec3f* velocity_out) {
  size_t k = 0;
  for (; k + 4 <= points.size(); k += 4)
    sums_of<4>(block, &points[k], positions, inv_h2, count_q2, count_out, kernel_out, velocity_out);
  for (; k < points.size(); ++k)
    sums_of<1>(block, &points[k], positions, inv_h2, count_q2, count_out, kernel_out, velocity_out);
}

}  // namespace spume
