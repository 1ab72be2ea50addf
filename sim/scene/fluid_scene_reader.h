#pragma once
// Reading the built-in fluid solver's settings from a scene (used when `fluid.source` is "solver"):
// the keys fluid.radius, rest_density, support_radius, blocks and fluid.solver.*, each declared once
// with its unit, default and range in keys/scene_keys.h (`spume keys fluid` lists them).
#include <vector>

#include "sim/core/params.h"
#include "sim/fluid/fluid_params.h"

namespace spume {

struct FluidSolverSetup {
  FluidSolverParams params;
  std::vector<FluidBlock> blocks;
};

// Reads the solver keys of the `fluid` object. `gravity` is the scene's (m/s^2). Errors name the
// file and key path.
FluidSolverSetup read_fluid_solver(const ParamReader& fluid, const Vec3f& gravity);

}  // namespace spume
