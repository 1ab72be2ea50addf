#pragma once
// The adaptive time step: a CFL condition with limits, and landing exactly on requested times.
#include <vector>

#include "sim/fluid/fluid_params.h"
#include "sim/fluid/particles.h"
#include "sim/geometry/solids.h"

namespace spume::fluid {

struct TimeStepChoice {
  double dt = 0.0;              // s
  bool clamped_to_min = false;  // the CFL condition asked for less than min_dt
  double max_speed = 0.0;       // m/s, the speed the step was sized for
};

// The starting fluid's depth D along g, m: the extent along g of the box around all blocks (the
// water a dropped block lands on counts with it). 0 without gravity.
double starting_depth(const std::vector<FluidBlock>& blocks, const Vec3f& gravity);

// The longest step deep water stays settled at: depth_cfl * 2r / sqrt(|g| D) (infinite when
// depth_cfl, g or D is 0). Each step gravity squeezes every layer by g dt^2 / 2r, and the density
// solve, which stops at an average tolerance, leaves a remainder that grows with the number of
// layers N = D / 2r below the surface; keeping (g dt^2 / 2r) N, that is (dt sqrt(|g| D) / 2r)^2,
// below a constant bounds it. Read as a CFL condition, sqrt(|g| D) is the speed of the fluid's
// gravity waves and of its collapse (sim/MODEL.md §10 gives the measurements behind 0.55).
double settling_step(const FluidSolverParams& params, double depth);

// The largest step a run starts with: min(max_dt, settling_step), never below min_dt.
double initial_step_cap(const FluidSolverParams& params, double depth);

// dt = cfl * 2r / u, u = the largest of |v_i + dt_prev a_i| (the speed after this step's non-pressure
// acceleration, so a fluid at rest under gravity is not given an unbounded step) and the speed of any
// moving solid at time t (and `body_speed`, the fastest point of any dynamic body); also at most
// h^2 / (32 nu) (explicit viscosity); clamped to [min_dt, step_cap] (step_cap >= min_dt: the
// solver's current cap, initial_step_cap lowered by retries). Max is exact, so this is
// thread-independent.
TimeStepChoice cfl_time_step(const FluidSolverParams& params, const Particles& p, double dt_prev,
                             const SolidSet& solids, double t, double step_cap, double body_speed = 0.0);

// Shortens dt so that stepping reaches `remaining` (s) exactly without a sliver step at the end: when
// remaining < 2 dt, the rest is split into halves (each at least dt / 2) or taken whole (also when
// it exceeds dt by at most 0.1%).
double fit_to_remaining(double dt, double remaining);

}  // namespace spume::fluid
