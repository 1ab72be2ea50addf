#include "sim/fluid/time_step.h"

#include <algorithm>
#include <cmath>

#include "sim/fluid/reduce.h"
#include "sim/keys/scene_keys.h"

namespace spume::fluid {

TimeStepChoice cfl_time_step(const FluidSolverParams& params, const Particles& p, double dt_prev,
                             const SolidSet& solids, double t, double body_speed) {
  const float fdt = float(dt_prev);
  const double v2 = chunked_max(p.size(), 0.0, [&](size_t b, size_t e) {
    float m = 0.0f;
    for (size_t i = b; i < e; ++i) m = std::max(m, (p.v[i] + fdt * p.accel[i]).squaredNorm());
    return double(m);
  });
  double speed = std::max(std::sqrt(v2), body_speed);
  for (const Solid& s : solids.solids())
    if (s.motion.moving()) speed = std::max(speed, double(s.motion.velocity(t).norm()));
  TimeStepChoice c;
  c.max_speed = speed;
  const double cfl_dt = speed > 0.0 ? double(params.cfl) * 2.0 * double(params.particle_radius) / speed : INFINITY;
  // Explicit diffusion is stable for dt <= h_s^2 / (8 nu) with the smoothing length h_s = h / 2.
  const double h = double(keys::fluid::support_radius_of(params.particle_radius));
  const double nu = std::max(params.viscosity, params.boundary_viscosity);
  const double viscous_dt = nu > 0.0 ? h * h / (32.0 * nu) : INFINITY;
  const double wanted = std::min(cfl_dt, viscous_dt);
  c.clamped_to_min = wanted < params.min_dt;
  c.dt = std::clamp(wanted, params.min_dt, params.max_dt);
  return c;
}

double fit_to_remaining(double dt, double remaining) {
  // Up to 0.1% beyond the CFL step is harmless, and absorbs rounding in the accumulated time (without
  // it, 4 steps of 5 ms to a 20 ms frame end could become 3 + 2 half steps).
  if (remaining <= dt * 1.001) return remaining;
  if (remaining < 2.0 * dt) return 0.5 * remaining;
  return dt;
}

}  // namespace spume::fluid
