#pragma once
// Which way is up in a cache whose files do not say (no Mantaflow config, a format without a
// convention), measured from a few of its frames as stored. Gravity shows in two ways a cache keeps:
//  - a free fall: the fluid keeps its shape (nothing holds it) while its centroid accelerates along
//    one axis, in three frames at equal intervals and of equal counts;
//  - a layer resting on a floor: in the last frame the fluid is much thinner along one axis than
//    along both others (a pool, a settled dam break), and at least 4 particle spacings thick there (a
//    quasi-2D slab of a few particles is not a layer that gravity flattened).
// The fall is the stronger evidence and wins when both are seen.
#include <string>
#include <vector>

#include "sim/core/frames.h"

namespace spume {

struct UpAxisMeasure {
  int axis = -1;    // 0, 1, 2 (x, y, z): the axis gravity acts along; -1 when nothing was measured
  int sign = 1;     // +1: the fluid falls toward -axis (up is +axis); -1: toward +axis; layers say +1
  bool by_fall = false;
  std::string how;  // what was measured (or why nothing was), for the log
};

// `frames`: a few frames of the sequence in frame order, as stored (not turned), with their `numbers`;
// `fps`: frames per second (for the acceleration in the log); `radius`: the particle radius r.
UpAxisMeasure measure_up_axis(const std::vector<FluidFrame>& frames, const std::vector<int>& numbers, double fps,
                              float radius);

}  // namespace spume
