#include "sim/fluid/blow_up.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/fluid/reduce.h"

namespace spume::fluid {
namespace {

// The solid's extent at its initial pose: rotated boxes and spheres by their bounding sphere.
Aabb solid_box(const Solid& s) {
  Aabb box;
  if (s.kind == Solid::Kind::Sphere) {
    box.extend(Vec3f(s.center - Vec3f::Constant(s.radius)));
    box.extend(Vec3f(s.center + Vec3f::Constant(s.radius)));
  } else if (s.kind == Solid::Kind::Box && s.rotated()) {
    const float reach = 0.5f * (s.max - s.min).norm();
    box.extend(Vec3f(s.centre() - Vec3f::Constant(reach)));
    box.extend(Vec3f(s.centre() + Vec3f::Constant(reach)));
  } else {
    box.extend(s.min);
    box.extend(s.max);
  }
  return box;
}

// The offsets a kinematic motion takes over all time, as a box around zero.
Aabb motion_range(const Motion& m) {
  Aabb range;
  range.extend(Vec3f::Zero());
  if (m.kind == Motion::Kind::Keyframes)
    for (const Vec3f& o : m.offsets) range.extend(o);
  if (m.kind == Motion::Kind::Sine) {
    const Vec3f reach = std::abs(m.amplitude) * m.axis.cwiseAbs();
    range.extend(reach);
    range.extend(Vec3f(-reach));
  }
  return range;
}

}  // namespace

Aabb scene_box(const std::vector<FluidBlock>& blocks, const SolidSet& solids) {
  Aabb box;
  for (const FluidBlock& b : blocks) {
    box.extend(b.min);
    box.extend(b.max);
  }
  for (const Solid& s : solids.solids()) {
    const Aabb at_rest = solid_box(s), range = motion_range(s.motion);
    box.extend(Vec3f(at_rest.min + range.min));
    box.extend(Vec3f(at_rest.max + range.max));
  }
  return box;
}

double fastest_solid_speed(const SolidSet& solids) {
  double fastest = 0.0;
  for (const Solid& s : solids.solids()) {
    const Motion& m = s.motion;
    if (m.kind == Motion::Kind::Sine)
      fastest = std::max(fastest, std::abs(double(m.amplitude)) * 2.0 * std::numbers::pi * double(m.frequency));
    if (m.kind == Motion::Kind::Keyframes)
      for (size_t k = 1; k < m.times.size(); ++k)
        if (m.times[k] > m.times[k - 1])
          fastest = std::max(fastest, double((m.offsets[k] - m.offsets[k - 1]).norm()) / (m.times[k] - m.times[k - 1]));
  }
  return fastest;
}

BlowUpLimits blow_up_limits(const FluidSolverParams& params, const std::vector<FluidBlock>& blocks,
                            const SolidSet& solids) {
  BlowUpLimits l;
  l.gravity = double(params.gravity.norm());
  if (l.gravity > 0.0) l.up = -params.gravity / params.gravity.norm();
  const Aabb box = scene_box(blocks, solids);
  if (!box.empty()) {
    // The box's extent along `up`: its lowest and highest corners.
    double lo = INFINITY, hi = -INFINITY;
    for (int c = 0; c < 8; ++c) {
      const Vec3f corner(c & 1 ? box.max.x() : box.min.x(), c & 2 ? box.max.y() : box.min.y(),
                         c & 4 ? box.max.z() : box.min.z());
      const double z = double(l.up.dot(corner));
      lo = std::min(lo, z), hi = std::max(hi, z);
    }
    l.bottom = lo;
    l.height = hi - lo;
  }
  l.solid_speed = fastest_solid_speed(solids);
  // A body denser than the water brings more energy per volume down the same height: a fluid
  // particle handed all of it moves at sqrt(2 |g| H rho_body / rho0).
  double densest = 1.0;
  for (const Solid& s : solids.solids())
    if (s.dynamics.enabled) {
      const double mass = s.dynamics.mass > 0.0f ? double(s.dynamics.mass) : double(s.dynamics.density) * s.volume();
      densest = std::max(densest, mass / (double(s.volume()) * double(params.rest_density)));
    }
  l.body_density_ratio = densest;
  l.reference_speed = std::max({std::sqrt(2.0 * l.gravity * l.height * densest), 2.0 * l.solid_speed, 1.0});
  l.max_fall_speed = kSpeedFactor * l.reference_speed;
  l.max_density_error = std::max(kMaxDensityError, 10.0 * double(params.density_tolerance));
  l.closed = !solids.any_dynamic() && std::none_of(solids.solids().begin(), solids.solids().end(),
                                                   [](const Solid& s) { return s.motion.moving(); });
  return l;
}

double fall_speed(const BlowUpLimits& limits, const Vec3f& x, const Vec3f& v) {
  const double z = double(limits.up.dot(x)) - limits.bottom;
  return std::sqrt(std::max(0.0, double(v.squaredNorm()) + 2.0 * limits.gravity * z));
}

double mean_energy(const BlowUpLimits& limits, const Particles& p) {
  if (p.size() == 0) return 0.0;
  const double sum = chunked_sum(p.size(), [&](size_t b, size_t e) {
    double s = 0.0;
    for (size_t i = b; i < e; ++i) {
      const double z = double(limits.up.dot(p.x[i])) - limits.bottom;
      s += 0.5 * double(p.v[i].squaredNorm()) + limits.gravity * z;
    }
    return s;
  });
  return sum / double(p.size());
}

void set_start_energy(BlowUpLimits& limits, const Particles& p) {
  if (!limits.closed) return;
  limits.start_energy = mean_energy(limits, p);
  limits.max_energy = limits.start_energy + kEnergySlack * limits.gravity * limits.height;
}

FastestParticle fastest_particle(const BlowUpLimits& limits, const Particles& p) {
  const size_t n = p.size();
  const size_t chunks = (n + kReduceChunk - 1) / kReduceChunk;
  std::vector<FastestParticle> best(chunks);
  parallel_for(chunks, 1, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      FastestParticle b{-1.0, c * kReduceChunk};
      for (size_t i = c * kReduceChunk; i < std::min(n, (c + 1) * kReduceChunk); ++i) {
        const double u = fall_speed(limits, p.x[i], p.v[i]);
        if (u > b.fall_speed) b = {u, i};
      }
      best[c] = b;
    }
  });
  FastestParticle out;
  for (const FastestParticle& b : best)
    if (b.fall_speed > out.fall_speed) out = b;
  return out;
}

void check_blow_up(const BlowUpLimits& limits, const FluidSolverParams& params, const Particles& p,
                   double density_error, double t) {
  // Formatted only when the run has blown up: this check runs after every step.
  auto advice = [&] {
    std::string a = str("; the solver is unstable at these settings: lower fluid.solver.max_dt (now ", params.max_dt,
                        " s), fluid.solver.depth_cfl (now ", params.depth_cfl, ") or fluid.solver.cfl (now ",
                        params.cfl, ")");
    if (!params.extrapolate_wall_pressure)
      a += "; deep water settles calmer with fluid.solver.wall_pressure = extrapolated (README: Deep water)";
    return a;
  };
  if (!(density_error <= limits.max_density_error))
    throw BlowUp(str("fluid solver blew up at t = ", t, " s: the average compression after the density solve is ",
                     100.0 * density_error, "%, above the bound ", 100.0 * limits.max_density_error,
                     "% (a converged solve leaves fluid.solver.density_tolerance, ",
                     100.0 * params.density_tolerance, "%)"),
                 advice());
  if (limits.closed && limits.gravity > 0.0) {
    const double e = mean_energy(limits, p);
    if (!(e <= limits.max_energy))
      throw BlowUp(str("fluid solver blew up at t = ", t, " s: the fluid's mechanical energy grew from ",
                       limits.start_energy, " to ", e, " J/kg, more than ", kEnergySlack, " x |g| H = ",
                       kEnergySlack * limits.gravity * limits.height,
                       " J/kg above its start, with nothing in the scene to drive it"),
                   advice());
  }
  const FastestParticle f = fastest_particle(limits, p);
  if (f.fall_speed > limits.max_fall_speed) {
    const size_t i = f.index;
    const std::string denser =
        limits.body_density_ratio > 1.0
            ? str(" (times sqrt(", limits.body_density_ratio, "), the densest body over the water)")
            : std::string();
    throw BlowUp(str("fluid solver blew up at t = ", t, " s: particle ", p.id[i], " moves at ", p.v[i].norm(),
                     " m/s at ", limits.up.dot(p.x[i]) - limits.bottom,
                     " m above the scene's bottom, so it would fall to the bottom at ", f.fall_speed,
                     " m/s, above the bound ", limits.max_fall_speed, " m/s = ", kSpeedFactor,
                     " x max(sqrt(2 |g| H) = ", std::sqrt(2.0 * limits.gravity * limits.height),
                     " m/s with H = ", limits.height, " m the height of the box around the fluid and solids",
                     denser, ", 2 x the fastest kinematic solid's ", limits.solid_speed, " m/s, 1 m/s)"),
                 advice());
  }
}

}  // namespace spume::fluid
