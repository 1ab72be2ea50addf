#pragma once
// The fluid around a point, from one block of neighbours: the count within sqrt(count_q2) of the
// weights' reach (inv_h2 = 1 / reach^2), the sum of poly6-shaped weights (1 - r^2/reach^2)^3 and the
// weighted mean velocity (attribute 0 of the block; zero when no weight). Shared by the diffuse
// particles' fluid sampling and the FLIP velocity smoothing.
#include <cstdint>
#include <span>

#include "sim/core/vec.h"
#include "sim/grid/block_buffer.h"

namespace spume {

void poly6_sums(const BlockBuffer& block, const Vec3f& p, float inv_h2, float count_q2, float& count_out,
                float& kernel_out, Vec3f& velocity_out);
// The same for each point positions[i], i in `points`, into count_out[i], kernel_out[i] and
// velocity_out[i], with the same results: a group of points that scan one block, four at a time, so
// that each block point is loaded once for all four.
void poly6_sums_for(const BlockBuffer& block, std::span<const uint32_t> points, const Vec3f* positions, float inv_h2,
                    float count_q2, float* count_out, float* kernel_out, Vec3f* velocity_out);

}  // namespace spume
