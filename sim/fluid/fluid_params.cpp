#include "sim/fluid/fluid_params.h"

#include <cmath>

#include "sim/core/error.h"

namespace spume {

void validate(const FluidSolverParams& p) {
  // The declared ranges (keys/scene_keys.h), for callers that fill the struct without a scene.
  auto check = [](const KeySpec& k, double v) {
    if (const std::string why = out_of_range(k, v); !why.empty()) fail("fluid solver: ", k.path, ": ", why);
  };
  namespace s = keys::solver;
  if (!(p.particle_radius > 0.0f) || !std::isfinite(p.particle_radius))
    fail("fluid solver: particle_radius = ", p.particle_radius, " must be a finite number > 0");
  check(keys::fluid::radius, p.particle_radius);
  check(keys::fluid::rest_density, p.rest_density);
  check(s::viscosity, p.viscosity);
  check(s::boundary_viscosity, p.boundary_viscosity);
  check(s::xsph, p.xsph);
  check(s::cfl, p.cfl);
  check(s::min_dt, p.min_dt);
  check(s::max_dt, p.max_dt);
  check(s::depth_cfl, p.depth_cfl);
  check(s::density_tolerance, p.density_tolerance);
  check(s::min_density_iterations, p.min_density_iterations);
  check(s::max_density_iterations, p.max_density_iterations);
  check(s::divergence_tolerance, p.divergence_tolerance);
  check(s::min_divergence_iterations, p.min_divergence_iterations);
  check(s::max_divergence_iterations, p.max_divergence_iterations);
  check(s::boundary_spacing, p.boundary_spacing);
  check(s::push_out_skin, p.push_out_skin);
  check(s::start_clearance, p.start_clearance);
  if (!finite(p.gravity)) fail("fluid solver: gravity must be finite");
  if (p.min_dt > p.max_dt) fail("fluid solver: min_dt ", p.min_dt, " is above max_dt ", p.max_dt);
  if (p.min_density_iterations > p.max_density_iterations)
    fail("fluid solver: min_density_iterations ", p.min_density_iterations, " is above max_density_iterations ",
         p.max_density_iterations);
  if (p.min_divergence_iterations > p.max_divergence_iterations)
    fail("fluid solver: min_divergence_iterations ", p.min_divergence_iterations,
         " is above max_divergence_iterations ", p.max_divergence_iterations);
}

}  // namespace spume
