#pragma once
// The adaptive time step: a CFL condition with limits, and landing exactly on requested times.
#include "sim/fluid/fluid_params.h"
#include "sim/fluid/particles.h"
#include "sim/geometry/solids.h"

namespace spume::fluid {

struct TimeStepChoice {
  double dt = 0.0;              // s
  bool clamped_to_min = false;  // the CFL condition asked for less than min_dt
  double max_speed = 0.0;       // m/s, the speed the step was sized for
};

// dt = cfl * 2r / u, u = the largest of |v_i + dt_prev a_i| (the speed after this step's non-pressure
// acceleration, so a fluid at rest under gravity is not given an unbounded step) and the speed of any
// moving solid at time t (and `body_speed`, the fastest point of any dynamic body); also at most h^2 / (32 nu) (explicit viscosity); clamped to
// [min_dt, max_dt]. Max is exact, so this is thread-independent.
TimeStepChoice cfl_time_step(const FluidSolverParams& params, const Particles& p, double dt_prev,
                             const SolidSet& solids, double t, double body_speed = 0.0);

// Shortens dt so that stepping reaches `remaining` (s) exactly without a sliver step at the end: when
// remaining < 2 dt, the rest is split into halves (each at least dt / 2) or taken whole (also when
// it exceeds dt by at most 0.1%).
double fit_to_remaining(double dt, double remaining);

}  // namespace spume::fluid
