#pragma once
// Parameters, initial fluid and statistics of spume's DFSPH fluid solver. SI units throughout.
// The keys, defaults and ranges are declared once, in keys/scene_keys.h (fluid.solver.*); the
// defaults here are those declarations, and validate() checks their ranges.
#include <array>
#include <cstdint>
#include <string_view>
#include <vector>

#include "sim/core/vec.h"
#include "sim/keys/scene_keys.h"

namespace spume {

struct FluidSolverParams {
  // Particles sit on a lattice of spacing 2r; the cubic spline kernel has support h = 4r.
  float particle_radius = 0.01f;  // r, m; for callers without a scene (a scene must give fluid.radius)
  float rest_density = declared_float(keys::fluid::rest_density);  // rho0, kg/m^3; mass rho0 (2r)^3
  // Kinematic viscosity nu (m^2/s) of the standard SPH Laplacian (forces.h). Water is 1e-6, which
  // leaves the solver's particle-scale noise undamped (a tank at rest keeps ~0.2 m/s rms for seconds,
  // measured); the default damps that noise at r ~ 5-10 mm within a fraction of a second (rate
  // ~10 nu / h^2) while a 1 m wave barely feels it (decay time L^2 / nu ~ 1000 s). Lower it for
  // livelier splashes at fine resolution.
  float viscosity = declared_float(keys::solver::viscosity);
  // Same term between fluid and solid particles: friction of the unresolved wall boundary layer,
  // m^2/s. 0 = free-slip walls. With the default, the dam-break surge front follows Martin & Moyce
  // (1952) within ~10%; free-slip walls run ~15-20% ahead (tests/sim/fluid_dam_break_test.cpp).
  float boundary_viscosity = declared_float(keys::solver::boundary_viscosity);
  // XSPH velocity smoothing [Monaghan 1989]: each step moves v_i this fraction of the way towards
  // the kernel average of its neighbours' velocities (dimensionless, 0..1). 0 = off.
  float xsph = declared_float(keys::solver::xsph);
  Vec3f gravity = declared_vec3<Vec3f>(keys::scene::gravity);  // m/s^2

  // Time step: dt = cfl * 2r / max speed (fluid and moving solids), also at most h^2 / (32 nu) for
  // the explicit viscosity to stay stable (h = 4r; binds only for large nu) and at most
  // depth_cfl * 2r / sqrt(|g| D) for deep water (time_step.h), clamped to [min_dt, max_dt].
  float cfl = declared_float(keys::solver::cfl);
  double min_dt = keys::solver::min_dt.value[0];  // s
  double max_dt = keys::solver::max_dt.value[0];  // s
  float depth_cfl = declared_float(keys::solver::depth_cfl);  // 0 = no depth limit

  // Constant-density solve: iterate until the average predicted compression (rho* - rho0) / rho0
  // over all particles (expansion counts as 0) is at most this; 0.0005 = 0.05%.
  float density_tolerance = declared_float(keys::solver::density_tolerance);
  int min_density_iterations = int(keys::solver::min_density_iterations.value[0]);
  int max_density_iterations = int(keys::solver::max_density_iterations.value[0]);
  // Divergence-free solve: iterate until the average compression rate times dt,
  // mean(max(D rho / Dt, 0)) dt / rho0, is at most this; 0.001 = 0.1% of rho0 per step.
  bool divergence_solve = keys::solver::divergence_solve.value[0] != 0.0;
  float divergence_tolerance = declared_float(keys::solver::divergence_tolerance);
  int min_divergence_iterations = int(keys::solver::min_divergence_iterations.value[0]);
  int max_divergence_iterations = int(keys::solver::max_divergence_iterations.value[0]);
  // Start each solve from half the previous step's pressure (pressure.h explains why it is off).
  bool warm_start = keys::solver::warm_start.value[0] != 0.0;

  // Boundary particles fill the solids to depth h on a lattice of this spacing, in units of r
  // (2 = the fluid's own spacing, which makes a wall read exactly as the missing fluid).
  float boundary_spacing = declared_float(keys::solver::boundary_spacing);
  // A fluid particle found inside a solid after a step is put this far (in units of r) outside it.
  float push_out_skin = declared_float(keys::solver::push_out_skin);
  // Starting lattice points closer than this (in units of r) to a box or sphere are left out, as
  // those inside are. A point that close overlaps the solid's boundary samples and is flung out on
  // the first steps (README, Deep water).
  float start_clearance = declared_float(keys::solver::start_clearance);
  // Walls press back with the fluid's pressure extrapolated into them (boundary_pressure.h), or, when
  // false, with each fluid particle's own pressure ([AIA12]). The default is the key's first choice.
  bool extrapolate_wall_pressure = std::string_view(keys::solver::wall_pressure.choices).starts_with("extrapolated");
};

// An initial cuboid of fluid, m. Filled on a lattice of spacing 2r centred in the box, so the
// particles' (2r)^3 cells tile as much of it as fits; lattice points inside solids are left out.
struct FluidBlock {
  Vec3f min = Vec3f::Zero(), max = Vec3f::Zero();
};

enum class FluidStage { Neighbours, Divergence, Forces, Density, Advect, Count };

struct SolverStats {
  uint64_t steps = 0;
  double time = 0.0;                    // s, simulated
  double average_dt = 0.0;              // s
  double min_dt_used = 0.0, max_dt_used = 0.0;  // s
  double average_density_iterations = 0.0;
  double average_divergence_iterations = 0.0;
  double density_error = 0.0;           // last step's average (rho* - rho0)+ / rho0 after the solve
  double max_density_error = 0.0;       // largest of those over all steps
  double divergence_error = 0.0;        // last step's average compression rate * dt / rho0
  uint64_t density_unconverged = 0;     // steps whose density solve hit the iteration limit
  uint64_t divergence_unconverged = 0;
  uint64_t corrections = 0;             // fluid particles projected out of a solid after a step
  uint64_t dt_clamped_to_min = 0;       // steps where the CFL step was below min_dt
  uint64_t retries = 0;                 // times a blown-up stretch was taken again with a smaller step
  double step_cap = 0.0;                // s: the largest step the solver takes now (time_step.h, retries)
  size_t fluid_particles = 0, boundary_particles = 0;
  size_t removed_at_start = 0;          // block lattice points left out because they were inside solids
  std::array<double, size_t(FluidStage::Count)> stage_seconds{};  // wall clock per stage
};

// Throws Error naming the first parameter out of range.
void validate(const FluidSolverParams& p);

}  // namespace spume
