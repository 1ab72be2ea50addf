#pragma once
// Whether two frames without particle ids may be paired by index: solvers reorder their particles
// (SPlisHSPlasH sorts them now and then, FLIP solvers reseed), and a file without ids does not say so.
#include <string>

#include "sim/core/frames.h"

namespace spume {

// "" when index i of `next` is where particle i of `current` went (equal counts assumed); else what
// was measured. Kept order: the median distance from where particle i's stored velocity (or, without
// one, its position) puts it to index i of `next` is under a quarter of the median distance between
// unrelated particles (i against i + n/2), about what a reordered frame misses by. Frames of fewer
// than 8 particles say nothing reliable and pass.
std::string index_order_mismatch(const FluidFrame& current, const FluidFrame& next, double frame_dt);

}  // namespace spume
