#include "fluid_scene_reader.h"

#include <cmath>

#include "core/error.h"

namespace spume {

FluidSolverSetup read_fluid_solver(const ParamReader& fluid, const Vec3f& gravity) {
  const FluidSolverParams defaults;
  FluidSolverSetup setup;
  FluidSolverParams& p = setup.params;

  if (!fluid.has("radius")) fluid.fail_at("radius", "missing: the fluid particle radius in m is required");
  p.particle_radius = float(fluid.number_in("radius", defaults.particle_radius, 1e-5, 10.0));
  p.rest_density = float(fluid.positive("rest_density", defaults.rest_density));
  if (fluid.has("support_radius")) {
    const double h = fluid.positive("support_radius", 4.0 * p.particle_radius);
    if (std::abs(h - 4.0 * p.particle_radius) > 1e-6 * h)
      fluid.fail_at("support_radius", str("the built-in solver uses h = 4 x radius = ", 4.0 * p.particle_radius,
                                          " m; found ", h, " (leave the key out)"));
  }
  p.gravity = gravity;

  const auto blocks = fluid.array_of_objects("blocks");
  if (blocks.empty()) fluid.fail_at("blocks", "missing: at least one {\"min\": [x,y,z], \"max\": [x,y,z]} in m");
  for (const ParamReader& b : blocks) {
    const auto lo = b.optional_vec3("min"), hi = b.optional_vec3("max");
    if (!lo) b.fail_at("min", "missing: the block's lower corner [x, y, z] in m");
    if (!hi) b.fail_at("max", "missing: the block's upper corner [x, y, z] in m");
    if (!(lo->array() < hi->array()).all()) b.fail_at("max", "must be above min on every axis");
    setup.blocks.push_back(FluidBlock{*lo, *hi});
  }

  const ParamReader s = fluid.child("solver");
  p.viscosity = float(s.number_in("viscosity", defaults.viscosity, 0.0, 10.0));
  p.boundary_viscosity = float(s.number_in("boundary_viscosity", defaults.boundary_viscosity, 0.0, 10.0));
  p.xsph = float(s.number_in("xsph", defaults.xsph, 0.0, 1.0));
  p.cfl = float(s.number_in("cfl", defaults.cfl, 1e-3, 1.0));
  p.min_dt = s.number_in("min_dt", defaults.min_dt, 1e-9, 1.0);
  p.max_dt = s.number_in("max_dt", defaults.max_dt, 1e-9, 1.0);
  if (p.min_dt > p.max_dt) s.fail_at("max_dt", str("value ", p.max_dt, " is below min_dt ", p.min_dt));
  p.density_tolerance = float(s.number_in("density_tolerance", defaults.density_tolerance, 1e-7, 0.1));
  p.min_density_iterations =
      int(s.integer_in("min_density_iterations", defaults.min_density_iterations, 0, 100000));
  p.max_density_iterations =
      int(s.integer_in("max_density_iterations", defaults.max_density_iterations, 1, 100000));
  if (p.min_density_iterations > p.max_density_iterations)
    s.fail_at("max_density_iterations", "must not be below min_density_iterations");
  p.divergence_solve = s.boolean("divergence_solve", defaults.divergence_solve);
  p.divergence_tolerance = float(s.number_in("divergence_tolerance", defaults.divergence_tolerance, 1e-7, 0.1));
  p.min_divergence_iterations =
      int(s.integer_in("min_divergence_iterations", defaults.min_divergence_iterations, 0, 100000));
  p.max_divergence_iterations =
      int(s.integer_in("max_divergence_iterations", defaults.max_divergence_iterations, 1, 100000));
  if (p.min_divergence_iterations > p.max_divergence_iterations)
    s.fail_at("max_divergence_iterations", "must not be below min_divergence_iterations");
  p.warm_start = s.boolean("warm_start", defaults.warm_start);
  p.boundary_spacing = float(s.number_in("boundary_spacing", defaults.boundary_spacing, 0.5, 2.0));
  p.push_out_skin = float(s.number_in("push_out_skin", defaults.push_out_skin, 0.0, 2.0));
  with_context(fluid.source() + ": " + fluid.path_of("solver"), [&] { validate(p); });
  return setup;
}

}  // namespace spume
