#pragma once
// Stopping a solver that has blown up, before it writes nonsense frames. Two bounds, checked after
// every step, that no healthy scene comes near:
//  - Density: the constant-density solve's final average compression above 10% (or 10 x
//    density_tolerance when that is larger). A converged solve leaves the tolerance, 0.05% by default.
//  - Energy: a particle's "fall speed" u = sqrt(|v|^2 + 2 |g| z), z its height above the bottom of
//    the scene's box (the box around the fluid blocks and the solids, kinematic ones over their whole
//    path), is the speed it would have at that bottom after falling without loss. Fluid released at
//    rest in the box has u <= U = sqrt(2 |g| H), H the box's height along g, and only moving solids add
//    energy, so u may not exceed kSpeedFactor = 5 times U_ref = max(U sqrt(rho_b / rho0) (a body of
//    density rho_b > rho0 brings that much more energy per volume down the same height), 2 x the
//    fastest kinematic solid's speed (a wall moving at w throws fluid at up to 2w), 1 m/s). Counting
//    height makes the bound one of energy, not of speed: a particle that spilled over a wall and
//    falls forever keeps its u, while one shot upwards by an unstable step does not escape the bound
//    by climbing.
//  - Energy, as a whole, in a closed scene (no moving solid, no dynamic body: nothing does work on
//    the fluid): the mean of u^2 / 2 over the particles, its mechanical energy per kg, may not grow
//    by more than kEnergySlack x |g| H over its start. The density solve's tolerance lets a little in
//    (the inviscid dam break of the stability suite gains 1.1% of g H); a step too long for the
//    water's depth gains far more long before any particle passes the bound above (a 10 m column at
//    40 ms steps: 18% of g H, its fastest particle at 4 m/s against a bound of 77).
// Measured, the largest u / U_ref over whole runs of the shipped scenes: dam break 1.79 (29k
// particles, a splash thrown up the far wall; 1.98 at 211k over its first second), tower 1.51,
// wave 1.50, lighthouse 1.13, ship 0.98; so 5 leaves a margin of 2.5 (6 in energy). With
// min_dt = max_dt = 1 s (one step a frame) the dam break reaches 4.9 at frame 6 and 23.6 at frame 7,
// the ship 7.4 at frame 11.
#include <cmath>
#include <string>
#include <vector>

#include "sim/core/error.h"
#include "sim/core/vec.h"
#include "sim/fluid/fluid_params.h"
#include "sim/fluid/particles.h"
#include "sim/geometry/solids.h"

namespace spume::fluid {

// What check_blow_up throws: the solver can take the stretch again with a smaller step (solver.h).
// what() is the finding followed by the advice; finding() alone says what passed which bound.
class BlowUp : public Error {
 public:
  BlowUp(const std::string& finding, const std::string& advice) : Error(finding + advice), finding_(finding) {}
  const std::string& finding() const { return finding_; }

 private:
  std::string finding_;
};

struct BlowUpLimits {
  Vec3f up = Vec3f::UnitY();       // -g / |g| (any unit vector when g = 0)
  double gravity = 0.0;            // |g|, m/s^2
  double bottom = 0.0;             // the scene box's lowest height along `up`, m
  double height = 0.0;             // H, the box's extent along `up`, m
  double solid_speed = 0.0;        // fastest kinematic solid, m/s
  double body_density_ratio = 1.0; // the densest dynamic body over rho0, at least 1
  double reference_speed = 0.0;    // U_ref, m/s
  double max_fall_speed = 0.0;     // bound on u, m/s
  double max_density_error = 0.0;  // bound on the density solve's final average compression
  bool closed = false;             // no moving solid and no dynamic body
  double start_energy = 0.0;       // closed scenes: mean u^2 / 2 at the start, J/kg (set by the solver)
  double max_energy = INFINITY;    // closed scenes: start_energy + kEnergySlack |g| H
};

// A healthy run stays below this multiple of U_ref in fall speed (measured above).
constexpr double kSpeedFactor = 5.0;
constexpr double kMaxDensityError = 0.10;
constexpr double kEnergySlack = 0.05;

BlowUpLimits blow_up_limits(const FluidSolverParams& params, const std::vector<FluidBlock>& blocks,
                            const SolidSet& solids);

// Mean u^2 / 2 over the particles, J/kg (fixed chunks: thread-independent).
double mean_energy(const BlowUpLimits& limits, const Particles& p);
// Sets start_energy and max_energy from the particles at the start (closed scenes only).
void set_start_energy(BlowUpLimits& limits, const Particles& p);

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

// Throws BlowUp saying what passed which bound and what to change, when a step at time t (s) left
// the density error `density_error` or a particle beyond the limits.
void check_blow_up(const BlowUpLimits& limits, const FluidSolverParams& params, const Particles& p,
                   double density_error, double t);

}  // namespace spume::fluid
