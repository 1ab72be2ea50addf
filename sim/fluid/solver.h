#pragma once
// spume's incompressible SPH fluid: DFSPH [BK15, BK17] with boundary particles (layers of frozen
// fluid inside the solids, boundary.h) pushing with Akinci's pressure force [AIA12], a CFL-adaptive
// time step, standard SPH viscosity and gravity, in SI units. Deterministic: results
// are bit-identical for any thread count (each parallel loop writes each element once; sums use
// fixed chunks, see reduce.h).
//
// One step (the simulation loop of [BK17], rotated so that it starts from fresh neighbourhoods):
//   1. sort the particles by grid cell, cache neighbour pairs, density and the DFSPH factor
//   2. divergence-free solve on v (pressure.h)
//   3. non-pressure accelerations a (forces.h); dt from the CFL and depth conditions (time_step.h)
//   4. v* = v + dt a; constant-density solve on v*
//   5. x += dt v; solids move to t + dt (dynamic bodies: Bullet steps them under gravity and the
//      fluid's forces on their boundary particles, coupling.h); any particle that entered a solid is
//      projected out
//
// Dynamic bodies ([AIA12]'s two-way coupling): during a step the fluid sees each body move rigidly
// at its velocity at the start of the step (v + w x r per boundary particle); the impulses the two
// pressure solves and the boundary viscosity give the fluid through the body's boundary particles
// go back to the body as a force and torque held over the step. The coupling is explicit: a body
// reacts one step late, which holds for a cube a tenth of the fluid's density. Known weakness of this
// explicit scheme: the pressure solve treats the body's velocity as given, so fluid squeezed between
// a body and a wall pushes as hard as it takes to get out of the way: a box twice the water's
// density landing on the tank floor through a one-particle film rebounds and spins before settling
// (tests/bench/RESULTS.md §6), one three times as dense blows the film out at any step. A last layer
// of particles stays trapped under a flat body resting on a wall. An implicit body-fluid solve would
// remove both (sim/MODEL.md §10).
//
// References: [BK15] Bender, Koschier: Divergence-free smoothed particle hydrodynamics, SCA 2015.
// [BK17] Bender, Koschier: Divergence-free SPH for incompressible and viscous fluids, IEEE TVCG 2017.
// [AIA12] Akinci, Ihmsen, Akinci, Solenthaler, Teschner: Versatile rigid-fluid coupling for
// incompressible SPH, ACM TOG (SIGGRAPH) 2012. [Mon05] Monaghan: Smoothed particle hydrodynamics,
// Rep. Prog. Phys. 68, 2005.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "sim/core/frames.h"
#include "sim/core/cubic_spline.h"
#include "sim/fluid/blow_up.h"
#include "sim/fluid/boundary.h"
#include "sim/fluid/coupling.h"
#include "sim/fluid/fluid_params.h"
#include "sim/fluid/neighbours.h"
#include "sim/fluid/boundary_pressure.h"
#include "sim/fluid/particles.h"
#include "sim/fluid/restart_state.h"
#include "sim/fluid/rigid_bodies.h"
#include "sim/grid/neighbour_grid.h"
#include "sim/geometry/solids.h"

namespace spume {

class FluidSolver {
 public:
  // Fills the blocks (see FluidBlock; lattice points inside solids or outside a tank are left out and
  // counted in stats().removed_at_start) and samples the solids. Throws Error for bad parameters,
  // bad solid motions, blocks that hold no particle, or a scene whose estimated memory
  // (memory_estimate.h) exceeds what the machine has available, before allocating anything.
  FluidSolver(FluidSolverParams params, const std::vector<FluidBlock>& blocks, SolidSet solids);

  // Steps until time() == t exactly (the last steps are fitted to land on t). No-op if t <= time().
  // `after_step`, if given, is called after every step (progress reports). When a step blows up
  // (blow_up.h), the whole stretch is taken again from the state advance_to started from with the
  // step cap set to half the longest step the stretch took (the CFL condition may have kept every
  // step far below the cap, and halving a cap no step reached retries the same steps). The cap stays
  // lowered for the rest of the run (stats().retries, .step_cap), up to kMaxRetries times and never
  // below min_dt; then the last BlowUp is rethrown with what was tried.
  // Every decision rests on thread-independent values, so the bytes are too. Dynamic bodies start
  // the stretch afresh from their poses (Bullet's contacts cleared), as a restored solver does.
  void advance_to(double t, const std::function<void()>& after_step = {});
  static constexpr int kMaxRetries = 4;
  // What the blow-up behind the last retry found (BlowUp::finding), "" when none has happened.
  const std::string& last_retry_reason() const { return last_retry_reason_; }
  // One step of at most the CFL time step; returns dt (s). Throws Error when the step blew up
  // (blow_up.h: a density error or a particle's energy past the limits), naming the value and bound.
  double step();

  // The state the next step starts from (restart_state.h), labelled with `frame`.
  FluidRestartState restart_state(int frame) const;
  // Continues from a saved state of a solver built with the same parameters, blocks and solids: every
  // later step gives the same bytes as the solver that saved it. Throws Error when the state does
  // not fit (particle count, ids, radius, warm start, the dynamic bodies).
  void restore(const FluidRestartState& state);

  // The current state in id order (ids 0..n-1), labelled with `index` and the current time.
  FluidFrame frame(int index) const;
  // What the diffuse model needs to know about this fluid (radius, h = 4r, rest density, fps).
  FluidSequenceInfo info(double fps) const;
  SolverStats stats() const;

  double time() const { return time_; }
  size_t size() const { return particles_.size(); }
  const FluidSolverParams& params() const { return params_; }
  // The solids as given (dynamic bodies at their initial pose).
  const SolidSet& solids() const { return solids_; }
  // The dynamic bodies' poses at time(), in solid order (empty without dynamic solids).
  const std::vector<BodyPose>& body_poses() const { return bodies_.poses(); }
  // The solids at time(): kinematic ones moved by their motion, dynamic ones at their current pose
  // (SolidSet::at_time(t).posed(body_poses())): what the fluid particles are kept out of.
  SolidSet solids_now() const;
  const fluid::RigidBodies& bodies() const { return bodies_; }
  const fluid::BlowUpLimits& blow_up_limits() const { return limits_; }
  float particle_volume() const { return volume_; }  // (2r)^3, m^3
  // Current per-particle density rho / rho0 (neighbourhoods are always built at the current
  // positions), in id order.
  std::vector<float> density_ratios() const;
  // Boundary particle positions at the current time (for inspection and tests).
  std::vector<Vec3f> boundary_positions() const;

 private:
  double step_to(double target);  // one step, shortened to land on target
  void update_neighbourhoods();
  // Throws BlowUp when a particle's position or velocity is not finite.
  void check_finite() const;
  void project_out_of_solids();
  // Per solid: where its boundary particles are at time t (kinematic motions, current body poses).
  std::vector<fluid::SolidPlacement> placements_at(double t) const;
  // The same with each kinematic solid's mean velocity over [t0, t1] (what moves it during a step).
  std::vector<fluid::SolidPlacement> step_placements(double t0, double t1) const;
  double body_speed() const;  // fastest point of any dynamic body, m/s
  void sync_body_centres();
  // What advance_to goes back to when a stretch blows up (the restart state, bodies included).
  void roll_back(const FluidRestartState& start);
  // Takes the particles, time, last step and counters of a state (restore and roll_back check and
  // place the rest).
  void adopt(const FluidRestartState& s);

  FluidSolverParams params_;
  SolidSet solids_;
  CubicSpline kernel_;
  float volume_;
  fluid::Particles particles_;
  fluid::Boundary boundary_;
  fluid::RigidBodies bodies_;
  fluid::CouplingBodies coupling_;
  fluid::BodyLoads loads_;
  std::vector<float> body_radius_;  // farthest point from the centre, per body, m
  NeighbourGrid grid_;
  fluid::Neighbourhoods neighbourhoods_;
  fluid::WallPressure walls_;
  fluid::WallPressure* walls_ptr() { return params_.extrapolate_wall_pressure ? &walls_ : nullptr; }
  fluid::BlowUpLimits limits_;
  double time_ = 0.0;
  double dt_prev_;
  double longest_choice_ = 0.0;  // the longest step the current stretch chose (before fitting), s
  std::string last_retry_reason_;
  SolverStats stats_;        // what stats() reports beyond counters_: particle counts, stage times
  SolverCounters counters_;  // step to step: behind stats() and carried by restart_state()
};

}  // namespace spume
