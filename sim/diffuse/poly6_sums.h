#pragma once
// The fluid around a point, from one block of neighbours: the count within sqrt(count_q2) of the
// weights' reach (inv_h2 = 1 / reach^2), the sum of poly6-shaped weights (1 - r^2/reach^2)^3 and the
// weighted mean velocity (attribute 0 of the block; zero when no weight). Shared by the diffuse
// particles' fluid sampling and the FLIP velocity smoothing.
#include "sim/core/vec.h"
#include "sim/grid/block_buffer.h"

namespace spume {

void poly6_sums(const BlockBuffer& block, const Vec3f& p, float inv_h2, float count_q2, float& count_out,
                float& kernel_out, Vec3f& velocity_out);

}  // namespace spume
