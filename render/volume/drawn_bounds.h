#pragma once
// The box around every drawn diffuse sphere of a frame, and how many there are: the volume pass's
// first look at the frame, which also refuses a frame it cannot draw.
#include <array>
#include <cstddef>

#include "sim/core/frames.h"
#include "sim/core/vec.h"

namespace spume {

// Spheres of radius[type] > 0 count (the others are not drawn). Fails naming the frame and the first
// particle whose type is not 0..2, or whose drawn sphere has a non-finite centre.
Aabb drawn_bounds(DiffuseView frame, const std::array<float, kDiffuseTypeCount>& radius, size_t& count);

}  // namespace spume
