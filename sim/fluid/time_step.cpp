#include "sim/fluid/time_step.h"

#include <algorithm>
#include <cmath>

#include "sim/fluid/reduce.h"
#include "sim/keys/scene_keys.h"

namespace spume::fluid {

double starting_depth(const std::vector<FluidBlock>& blocks, const Vec3f& gravity) {
  if (blocks.empty() || !(gravity.norm() > 0.0f)) return 0.0;
  const Vec3f up = -gravity.normalized();
  double lo = INFINITY, hi = -INFINITY;
  for (const FluidBlock& b : blocks)
    for (int c = 0; c < 8; ++c) {
      const Vec3f corner(c & 1 ? b.max.x() : b.min.x(), c & 2 ? b.max.y() : b.min.y(), c & 4 ? b.max.z() : b.min.z());
      const double z = double(up.dot(corner));
      lo = std::min(lo, z), hi = std::max(hi, z);
    }
  return hi - lo;
}

double settling_step(const FluidSolverParams& params, double depth) {
  const double g = double(params.gravity.norm());
  if (!(params.depth_cfl > 0.0f) || !(g > 0.0) || !(depth > 0.0)) return INFINITY;
  return double(params.depth_cfl) * 2.0 * double(params.particle_radius) / std::sqrt(g * depth);
}

double initial_step_cap(const FluidSolverParams& params, double depth) {
  return std::max(params.min_dt, std::min(params.max_dt, settling_step(params, depth)));
}

TimeStepChoice cfl_time_step(const FluidSolverParams& params, const Particles& p, double dt_prev,
                             const SolidSet& solids, double t, double step_cap, double body_speed) {
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
  c.dt = std::clamp(wanted, params.min_dt, std::max(params.min_dt, step_cap));
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
