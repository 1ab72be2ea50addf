#include "sim/scene/fluid_scene_reader.h"

#include <cmath>

#include "sim/core/error.h"
#include "sim/keys/scene_keys.h"

namespace spume {

FluidSolverSetup read_fluid_solver(const ParamReader& fluid, const Vec3f& gravity) {
  namespace f = keys::fluid;
  namespace k = keys::solver;
  FluidSolverSetup setup;
  FluidSolverParams& p = setup.params;

  p.particle_radius = float(fluid.number(f::radius));
  p.rest_density = float(fluid.number(f::rest_density));
  if (fluid.has(f::support_radius.name())) {
    const double h = fluid.number(f::support_radius, p.particle_radius);
    const double solver_h = f::support_radius_of(p.particle_radius);
    if (std::abs(h - solver_h) > 1e-6 * h)
      fluid.fail_at("support_radius", str("the built-in solver uses h = ", f::kSupportFactor, " x radius = ", solver_h,
                                          " m; found ", h, " (leave the key out)"));
  }
  p.gravity = gravity;

  const auto blocks = fluid.array_of_objects(f::blocks.name());
  if (blocks.empty()) fluid.fail_at("blocks", "missing: at least one {\"min\": [x,y,z], \"max\": [x,y,z]} in m");
  for (const ParamReader& b : blocks) {
    const Vec3f lo = b.vec3(f::block_min), hi = b.vec3(f::block_max);
    if (!(lo.array() < hi.array()).all()) b.fail_at("max", "must be above min on every axis");
    setup.blocks.push_back(FluidBlock{lo, hi});
  }

  const ParamReader s = fluid.child("solver");
  p.viscosity = float(s.number(k::viscosity));
  p.boundary_viscosity = float(s.number(k::boundary_viscosity));
  p.xsph = float(s.number(k::xsph));
  p.cfl = float(s.number(k::cfl));
  p.min_dt = s.number(k::min_dt);
  p.max_dt = s.number(k::max_dt);
  if (p.min_dt > p.max_dt) s.fail_at("max_dt", str("value ", p.max_dt, " is below min_dt ", p.min_dt));
  p.depth_cfl = float(s.number(k::depth_cfl));
  p.density_tolerance = float(s.number(k::density_tolerance));
  p.min_density_iterations = int(s.integer(k::min_density_iterations));
  p.max_density_iterations = int(s.integer(k::max_density_iterations));
  if (p.min_density_iterations > p.max_density_iterations)
    s.fail_at("max_density_iterations", "must not be below min_density_iterations");
  p.divergence_solve = s.boolean(k::divergence_solve);
  p.divergence_tolerance = float(s.number(k::divergence_tolerance));
  p.min_divergence_iterations = int(s.integer(k::min_divergence_iterations));
  p.max_divergence_iterations = int(s.integer(k::max_divergence_iterations));
  if (p.min_divergence_iterations > p.max_divergence_iterations)
    s.fail_at("max_divergence_iterations", "must not be below min_divergence_iterations");
  p.warm_start = s.boolean(k::warm_start);
  p.boundary_spacing = float(s.number(k::boundary_spacing));
  p.push_out_skin = float(s.number(k::push_out_skin));
  p.start_clearance = float(s.number(k::start_clearance));
  p.extrapolate_wall_pressure = s.choice(k::wall_pressure) == "extrapolated";
  with_context(fluid.source() + ": " + fluid.path_of("solver"), [&] { validate(p); });
  return setup;
}

}  // namespace spume
