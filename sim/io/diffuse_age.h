#pragma once
// How old each diffuse particle is, in seconds, read from its id: the id holds the step it was born in
// (core/frames.h), and the diffuse stage numbers its steps frame x substeps (diffuse/simulator.cpp),
// so at frame f a particle born in step s is f x substeps - s steps of 1 / (fps x substeps) s old.
// Exact to float rounding: a particle born at frame f's own classification is 0 s old there.
#include <vector>

#include "sim/core/frames.h"

namespace spume {

std::vector<float> diffuse_ages(const DiffuseFrame& frame, int substeps, double fps);

}  // namespace spume
