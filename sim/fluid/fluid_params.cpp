#include "fluid_params.h"

#include <cmath>

#include "core/error.h"

namespace spume {

void validate(const FluidSolverParams& p) {
  auto positive = [](const char* name, double v) {
    if (!(v > 0.0) || !std::isfinite(v)) fail("fluid solver: ", name, " = ", v, " must be a finite number > 0");
  };
  positive("particle_radius", p.particle_radius);
  positive("rest_density", p.rest_density);
  positive("cfl", p.cfl);
  positive("min_dt", p.min_dt);
  positive("max_dt", p.max_dt);
  positive("density_tolerance", p.density_tolerance);
  positive("divergence_tolerance", p.divergence_tolerance);
  positive("boundary_spacing", p.boundary_spacing);
  if (!(p.viscosity >= 0.0f) || !std::isfinite(p.viscosity)) fail("fluid solver: viscosity must be >= 0");
  if (!(p.boundary_viscosity >= 0.0f) || !std::isfinite(p.boundary_viscosity))
    fail("fluid solver: boundary_viscosity must be >= 0");
  if (!(p.xsph >= 0.0f) || p.xsph > 1.0f) fail("fluid solver: xsph ", p.xsph, " must be in [0, 1]");
  if (!finite(p.gravity)) fail("fluid solver: gravity must be finite");
  if (p.min_dt > p.max_dt) fail("fluid solver: min_dt ", p.min_dt, " is above max_dt ", p.max_dt);
  if (p.min_density_iterations < 0 || p.max_density_iterations < 1 ||
      p.min_density_iterations > p.max_density_iterations)
    fail("fluid solver: density iterations need 0 <= min <= max and max >= 1");
  if (p.min_divergence_iterations < 0 || p.max_divergence_iterations < 1 ||
      p.min_divergence_iterations > p.max_divergence_iterations)
    fail("fluid solver: divergence iterations need 0 <= min <= max and max >= 1");
  if (!(p.push_out_skin >= 0.0f) || p.push_out_skin > 2.0f) fail("fluid solver: push_out_skin must be in [0, 2] r");
  if (p.boundary_spacing < 0.5f || p.boundary_spacing > 2.0f)
    fail("fluid solver: boundary_spacing ", p.boundary_spacing, " r is outside [0.5, 2] r");
}

}  // namespace spume
