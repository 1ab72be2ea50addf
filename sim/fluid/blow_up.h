#pragma once
// Stopping a solver that has blown up, before it writes nonsense frames. Two bounds, checked after
// every step, that no healthy scene comes near:
//  - Density: the constant-density solve's final average compression above 10% (or 10 x
//    density_tolerance when that is larger). A converged solve leaves the tolerance, 0.05% by default.
//  - Energy: a particle's "fall speed" u = sqrt(|v|^2 + 2 |g| z), z its height above the bottom of
//    the scene's box (the box around the fluid blocks and the solids, kinematic ones over their whole
//    path), is the speed it would have at that bottom after falling without loss. Fluid released at
//    rest in the box has u <= U = sqrt(2 |g| H), H the box's height along g, and only moving solids add
//    energy, so u may not exceed kSpeedFactor = 5 times U_ref = max(U, 2 x the fastest kinematic
//    solid's speed (a wall moving at w throws fluid at up to 2w), 1 m/s). Counting height makes the
//    bound one of energy, not of speed: a particle that spilled over a wall and falls forever keeps its
//    u, while one shot upwards by an unstable step does not escape the bound by climbing.
// Measured, the largest u / U_ref over whole runs of the shipped scenes: dam break 1.79 (29k
// particles, a splash thrown up the far wall; 1.98 at 211k over its first second), tower 1.51,
// wave 1.50, lighthouse 1.13, ship 0.98; so 5 leaves a margin of 2.5 (6 in energy). With
// min_dt = max_dt = 1 s (one step a frame) the dam break reaches 4.9 at frame 6 and 23.6 at frame 7,
// the ship 7.4 at frame 11.
#include <string>
#include <vector>

#include "sim/core/vec.h"
#include "sim/fluid/fluid_params.h"
#include "sim/fluid/particles.h"
#include "sim/geometry/solids.h"

namespace spume::fluid {

struct BlowUpLimits {
  Vec3f up = Vec3f::UnitY();       // -g / |g| (any unit vector when g = 0)
  double gravity = 0.0;            // |g|, m/s^2
  double bottom = 0.0;             // the scene box's lowest height along `up`, m
  double height = 0.0;             // H, the box's extent along `up`, m
  double solid_speed = 0.0;        // fastest kinematic solid, m/s
  double reference_speed = 0.0;    // U_ref, m/s
  double max_fall_speed = 0.0;     // bound on u, m/s
  double max_density_error = 0.0;  // bound on the density solve's final average compression
};

// A healthy run stays below this multiple of U_ref in fall speed (measured above).
constexpr double kSpeedFactor = 5.0;
// Deep water at fine r blows up at the default max_dt (README, Deep fluid against walls): gravity
// squeezes the floor layers by g dt^2 / 2r a step, and the columns measured ran healthy with the
// extrapolated wall pressure at dt = c sqrt(2 r / |g|) for c = 0.026-0.065 and not from 0.079 on
// (r = 7.3 mm and 2.6 mm, 135-137 layers deep). The blow-up message suggests c = 0.04.
constexpr double kDeepWaterStepFactor = 0.04;
constexpr double kMaxDensityError = 0.10;

BlowUpLimits blow_up_limits(const FluidSolverParams& params, const std::vector<FluidBlock>& blocks,
                            const SolidSet& solids);

// The box around the fluid blocks and the solids (kinematic ones over their whole path).
Aabb scene_box(const std::vector<FluidBlock>& blocks, const SolidSet& solids);
// The fastest any kinematic solid moves at any time, m/s.
double fastest_solid_speed(const SolidSet& solids);

// u = sqrt(|v|^2 + 2 |g| z) of one particle (z may be negative below the box).
double fall_speed(const BlowUpLimits& limits, const Vec3f& x, const Vec3f& v);

struct FastestParticle {
  double fall_speed = 0.0;  // m/s
  size_t index = 0;         // into the particle arrays
};
// The particle of largest fall speed (the lowest index among equals: thread-independent).
FastestParticle fastest_particle(const BlowUpLimits& limits, const Particles& p);

// Throws Error saying what passed which bound and what to change, when a step at time t (s) left
// the density error `density_error` or a particle beyond the limits.
void check_blow_up(const BlowUpLimits& limits, const FluidSolverParams& params, const Particles& p,
                   double density_error, double t);

}  // namespace spume::fluid
