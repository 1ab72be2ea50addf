#pragma once
// Reading the built-in fluid solver's settings from a scene (used when `fluid.source` is "solver").
// Every key is in SI units; absent keys take FluidSolverParams' defaults (the only defaults).
//
//   "fluid": {
//     "source": "solver",                 // read by read_sim_scene, not here
//     "radius": 0.01,                     // m, required: particle radius r (spacing 2r, support h = 4r)
//     "rest_density": 1000,               // kg/m^3
//     "support_radius": 0.04,             // m, optional; must equal 4 * radius for the solver
//     "blocks": [{"min": [0, 0, 0], "max": [0.5, 1, 0.5]}],   // m, at least one initial fluid cuboid
//     "solver": {
//       "viscosity": 1e-3,                // m^2/s, kinematic, standard SPH Laplacian
//       "boundary_viscosity": 1e-3,       // m^2/s, fluid-solid friction (0 = free slip)
//       "xsph": 0,                        // dimensionless velocity smoothing, 0..1
//       "cfl": 0.4,                       // dt = cfl * 2r / max speed
//       "min_dt": 1e-5, "max_dt": 0.005,  // s
//       "density_tolerance": 0.0005,      // average relative compression (0.05%)
//       "min_density_iterations": 2, "max_density_iterations": 100,
//       "divergence_solve": true,
//       "divergence_tolerance": 0.001,    // average compression rate * dt / rho0 (0.1%)
//       "min_divergence_iterations": 1, "max_divergence_iterations": 100,
//       "warm_start": false,
//       "boundary_spacing": 2,            // boundary lattice spacing in units of r
//       "push_out_skin": 1                // in units of r
//     }
//   }
#include <vector>

#include "core/params.h"
#include "fluid/fluid_params.h"

namespace spume {

struct FluidSolverSetup {
  FluidSolverParams params;
  std::vector<FluidBlock> blocks;
};

// Reads the solver keys of the `fluid` object. `gravity` is the scene's (m/s^2). Errors name the
// file and key path.
FluidSolverSetup read_fluid_solver(const ParamReader& fluid, const Vec3f& gravity);

}  // namespace spume
