#include "sim/fluid/solver.h"

#include <algorithm>
#include <cmath>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/core/stopwatch.h"
#include "sim/fluid/forces.h"
#include "sim/fluid/memory_estimate.h"
#include "sim/fluid/pressure.h"
#include "sim/fluid/reduce.h"
#include "sim/fluid/time_step.h"
#include "sim/keys/scene_keys.h"

namespace spume {
namespace {

// Adds the wall-clock time of its scope to a stage's total.
class StageTimer {
 public:
  explicit StageTimer(double& seconds) : seconds_(seconds) {}
  ~StageTimer() { seconds_ += watch_.seconds(); }

 private:
  double& seconds_;
  Stopwatch watch_;
};

}  // namespace

FluidSolver::FluidSolver(FluidSolverParams params, const std::vector<FluidBlock>& blocks, SolidSet solids)
    : params_(params), solids_(std::move(solids)), kernel_(keys::fluid::support_radius_of(params.particle_radius)) {
  validate(params_);
  solids_.validate();
  fluid::check_memory(fluid::estimate_memory(params_, blocks, solids_), available_memory_bytes());
  limits_ = fluid::blow_up_limits(params_, blocks, solids_);
  const float r = params_.particle_radius;
  volume_ = 8.0f * r * r * r;
  counters_.step_cap = fluid::initial_step_cap(params_, fluid::starting_depth(blocks, params_.gravity));
  dt_prev_ = counters_.step_cap;
  const SolidSet now = solids_.at_time(0.0);
  particles_ = fluid::fill_blocks(blocks, r, now, params_.start_clearance * r, stats_.removed_at_start);
  if (particles_.size() == 0) fail("fluid solver: the fluid blocks hold no particles at radius ", r, " m");
  bodies_ = fluid::RigidBodies(solids_, params_.gravity, 0.5f * r, 2.0f * r);
  coupling_.body_of_solid.resize(solids_.solids().size());
  for (size_t s = 0; s < solids_.solids().size(); ++s) coupling_.body_of_solid[s] = bodies_.body_of_solid(s);
  for (const BodyPose& pose : bodies_.poses()) {
    const Solid& s = solids_.solids()[pose.solid];
    body_radius_.push_back(s.kind == Solid::Kind::Sphere ? s.radius : 0.5f * (s.max - s.min).norm());
  }
  sync_body_centres();
  boundary_ = fluid::sample_boundary(solids_, params_.boundary_spacing * r, kernel_.h);
  fluid::place_boundary(boundary_, placements_at(0.0), true);
  fluid::set_start_energy(limits_, particles_);
  stats_.fluid_particles = particles_.size();
  stats_.boundary_particles = boundary_.size();
  update_neighbourhoods();
}

std::vector<fluid::SolidPlacement> FluidSolver::placements_at(double t) const {
  const auto& list = solids_.solids();
  std::vector<fluid::SolidPlacement> out(list.size());
  for (size_t s = 0; s < list.size(); ++s) {
    out[s].translation = list[s].motion.offset(t);
    out[s].velocity = list[s].motion.velocity(t);
  }
  for (const BodyPose& pose : bodies_.poses()) {
    fluid::SolidPlacement& s = out[pose.solid];
    s.body = true;
    s.translation = pose.position;
    s.rotation = pose.orientation.toRotationMatrix();
    s.velocity = pose.velocity;
    s.angular_velocity = pose.angular_velocity;
  }
  return out;
}

std::vector<fluid::SolidPlacement> FluidSolver::step_placements(double t0, double t1) const {
  std::vector<fluid::SolidPlacement> out = placements_at(t0);
  const auto& list = solids_.solids();
  for (size_t s = 0; s < list.size(); ++s)
    if (!out[s].body)
      out[s].velocity =
          ((list[s].motion.offset(t1) - list[s].motion.offset(t0)).cast<double>() / (t1 - t0)).cast<float>();
  return out;
}

double FluidSolver::body_speed() const {
  double speed = 0.0;
  for (size_t k = 0; k < bodies_.size(); ++k) {
    const BodyPose& pose = bodies_.poses()[k];
    speed = std::max(speed, double(pose.velocity.norm()) + double(pose.angular_velocity.norm()) * body_radius_[k]);
  }
  return speed;
}

void FluidSolver::sync_body_centres() {
  coupling_.centre.clear();
  for (const BodyPose& pose : bodies_.poses()) coupling_.centre.push_back(pose.position);
}

SolidSet FluidSolver::solids_now() const {
  SolidSet now = solids_.at_time(time_);
  return bodies_.empty() ? now : now.posed(bodies_.poses());
}

void FluidSolver::update_neighbourhoods() {
  StageTimer timer(stats_.stage_seconds[size_t(FluidStage::Neighbours)]);
  grid_.build(particles_.x, kernel_.h);
  particles_.reorder(grid_.sorted_to_original());
  fluid::build_neighbourhoods(grid_, boundary_, kernel_, volume_, particles_, neighbourhoods_);
  if (walls_ptr()) walls_.build(neighbourhoods_, boundary_, kernel_, particles_, params_.gravity);
}

void FluidSolver::advance_to(double t, const std::function<void()>& after_step) {
  if (!(time_ < t)) return;
  // Bullet starts every stretch afresh from the bodies' poses (contacts and warm-started impulses
  // cleared): its state is then all in the poses, which a restart state carries, so a run continued
  // from one steps as one uninterrupted run does; a retry starts from the same state.
  if (!bodies_.empty()) bodies_.reset(bodies_.poses(), time_);
  const FluidRestartState start = restart_state(0);
  for (int attempt = 0;; ++attempt) {
    longest_choice_ = 0.0;
    try {
      while (time_ < t) {
        step_to(t);
        if (after_step) after_step();
      }
      return;
    } catch (const fluid::BlowUp& e) {
      const double cap =
          longest_choice_ > 0.0 ? std::min(counters_.step_cap, longest_choice_) : counters_.step_cap;
      if (attempt == kMaxRetries || cap <= params_.min_dt)
        throw fluid::BlowUp(e.what(), attempt ? str(" (taken again ", attempt, attempt == 1 ? " time" : " times",
                                                     " from t = ", start.time, " s with steps down to ", cap, " s)")
                                              : str(" (not taken again: its steps were already at fluid.solver.min_dt, ",
                                                    params_.min_dt, " s)"));
      roll_back(start);
      ++counters_.retries;
      counters_.step_cap = std::max(params_.min_dt, 0.5 * cap);
      last_retry_reason_ = e.finding();
    }
  }
}

void FluidSolver::roll_back(const FluidRestartState& start) {
  const double cap = counters_.step_cap;
  const uint64_t retries = counters_.retries;
  adopt(start);
  counters_.step_cap = cap, counters_.retries = retries;  // what the retries learnt stays
  if (!bodies_.empty()) {
    bodies_.reset(start.bodies, time_);
    sync_body_centres();
  }
  fluid::place_boundary(boundary_, placements_at(time_), false);
  update_neighbourhoods();
}

void FluidSolver::adopt(const FluidRestartState& s) {
  fluid::Particles& p = particles_;
  p.id = s.ids;
  p.x = s.positions;
  p.v = s.velocities;
  if (params_.warm_start) {
    p.density_warm = s.density_warm;
    p.divergence_warm = s.divergence_warm;
  }
  time_ = s.time;
  dt_prev_ = s.dt_prev;
  counters_ = s.counters;
}

double FluidSolver::step() { return step_to(INFINITY); }

double FluidSolver::step_to(double target) {
  auto& seconds = stats_.stage_seconds;
  fluid::Particles& p = particles_;
  const size_t n = p.size();
  const bool coupled = !bodies_.empty();
  const float particle_mass = params_.rest_density * volume_;
  if (coupled) loads_.reset(bodies_.size());

  // Divergence-free solve at the current positions ([BK17], divergence-free solver). Its result does not depend on
  // dt except through the error measure, so the previous step size is used.
  if (params_.divergence_solve) {
    StageTimer timer(seconds[size_t(FluidStage::Divergence)]);
    const fluid::SolveResult r = fluid::divergence_solve(params_, neighbourhoods_, boundary_, dt_prev_, p, walls_ptr());
    counters_.divergence_iterations += uint64_t(r.iterations);
    counters_.divergence_error = r.error;
    counters_.divergence_unconverged += r.converged ? 0 : 1;
    if (coupled) fluid::add_pressure_impulse(neighbourhoods_, boundary_, walls_ptr(), coupling_, particle_mass, dt_prev_, p, loads_);
  }

  double dt;
  {
    StageTimer timer(seconds[size_t(FluidStage::Forces)]);
    fluid::non_pressure_accelerations(params_, neighbourhoods_, boundary_, kernel_.h, volume_, dt_prev_, p);
    if (coupled)
      fluid::add_viscous_force(params_, neighbourhoods_, boundary_, coupling_, particle_mass, kernel_.h, p, loads_);
    const fluid::TimeStepChoice choice =
        fluid::cfl_time_step(params_, p, dt_prev_, solids_, time_, counters_.step_cap, body_speed());
    counters_.dt_clamped_to_min += choice.clamped_to_min ? 1 : 0;
    longest_choice_ = std::max(longest_choice_, choice.dt);
    dt = fluid::fit_to_remaining(choice.dt, target - time_);
  }
  const double t_end = dt == target - time_ ? target : time_ + dt;
  double density_error = 0.0;

  // Predict velocities, then make the density after this step rho0 ([BK17], constant-density solver).
  {
    StageTimer timer(seconds[size_t(FluidStage::Density)]);
    const float fdt = float(dt);
    parallel_for(n, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) p.v[i] += fdt * p.accel[i];
    });
    if (boundary_.any_moving) fluid::set_boundary_velocity(boundary_, step_placements(time_, t_end));
    const fluid::SolveResult r = fluid::density_solve(params_, neighbourhoods_, boundary_, dt, p, walls_ptr());
    counters_.density_iterations += uint64_t(r.iterations);
    density_error = r.error;
    counters_.density_error = r.error;
    counters_.max_density_error = std::max(counters_.max_density_error, r.error);
    counters_.density_unconverged += r.converged ? 0 : 1;
    if (coupled) fluid::add_pressure_impulse(neighbourhoods_, boundary_, walls_ptr(), coupling_, particle_mass, dt, p, loads_);
  }

  // Advect, move the solids, and keep every particle in free space.
  {
    StageTimer timer(seconds[size_t(FluidStage::Advect)]);
    const float fdt = float(dt);
    parallel_for(n, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) p.x[i] += fdt * p.v[i];
    });
    check_finite();  // before the bodies take the fluid's loads: a body at a NaN pose cannot be placed
    if (coupled) {
      std::vector<Vec3d> force, torque;
      loads_.totals(dt, force, torque);
      bodies_.step(time_, dt, force, torque);
      sync_body_centres();
    }
    time_ = t_end;
    fluid::place_boundary(boundary_, placements_at(time_), false);
    project_out_of_solids();
    fluid::check_blow_up(limits_, params_, p, density_error, time_);
  }

  dt_prev_ = dt;
  ++counters_.steps;
  counters_.dt_sum += dt;
  counters_.min_dt_used = counters_.steps == 1 ? dt : std::min(counters_.min_dt_used, dt);
  counters_.max_dt_used = std::max(counters_.max_dt_used, dt);
  update_neighbourhoods();
  return dt;
}

void FluidSolver::check_finite() const {
  const fluid::Particles& p = particles_;
  const size_t n = p.size();
  // Counts are exact integers in double, so the sum is thread-independent anyway.
  const double bad = fluid::chunked_sum(n, [&](size_t b, size_t e) {
    double count = 0.0;
    for (size_t i = b; i < e; ++i) count += finite(p.x[i]) && finite(p.v[i]) ? 0.0 : 1.0;
    return count;
  });
  if (bad > 0.0)
    for (size_t i = 0; i < n; ++i)
      if (!finite(p.x[i]) || !finite(p.v[i]))
        throw fluid::BlowUp(str("fluid solver: particle ", p.id[i], " has a non-finite position or velocity at t = ",
                                time_, " s (", uint64_t(bad), " particles in all)"),
                            "; try a smaller max_dt or cfl");
}

void FluidSolver::project_out_of_solids() {
  fluid::Particles& p = particles_;
  const size_t n = p.size();
  const SolidSet now = solids_now();
  const float skin = params_.push_out_skin * params_.particle_radius;
  if (now.empty()) return;
  const double moved = fluid::chunked_sum(n, [&](size_t b, size_t e) {
    double count = 0.0;
    for (size_t i = b; i < e; ++i) count += now.push_out(p.x[i], p.v[i], skin) ? 1.0 : 0.0;
    return count;
  });
  counters_.corrections += uint64_t(moved);
}

FluidRestartState FluidSolver::restart_state(int frame) const {
  const fluid::Particles& p = particles_;
  FluidRestartState s;
  s.frame = frame;
  s.time = time_;
  s.dt_prev = dt_prev_;
  s.particle_radius = params_.particle_radius;
  s.counters = counters_;
  s.ids = p.id;
  s.positions = p.x;
  s.velocities = p.v;
  if (params_.warm_start) {  // never read otherwise
    s.density_warm = p.density_warm;
    s.divergence_warm = p.divergence_warm;
  }
  s.bodies = bodies_.poses();
  return s;
}

void FluidSolver::restore(const FluidRestartState& s) {
  const size_t n = particles_.size();
  if (s.bodies.size() != bodies_.size())
    fail("fluid solver: the saved state has ", s.bodies.size(), " dynamic bodies; the scene has ", bodies_.size());
  for (size_t k = 0; k < s.bodies.size(); ++k)
    if (s.bodies[k].solid != bodies_.poses()[k].solid)
      fail("fluid solver: the saved state's body ", k, " is solid ", s.bodies[k].solid, "; the scene's is solid ",
           bodies_.poses()[k].solid);
  if (s.size() != n || s.positions.size() != n || s.velocities.size() != n)
    fail("fluid solver: the saved state has ", s.size(), " particles; the scene makes ", n);
  if (s.particle_radius != params_.particle_radius)
    fail("fluid solver: the saved state has particle radius ", s.particle_radius, " m; the scene ",
         params_.particle_radius, " m");
  if (params_.warm_start && (s.density_warm.size() != n || s.divergence_warm.size() != n))
    fail("fluid solver: warm_start is on but the saved state holds no warm-start pressures");
  if (!(s.dt_prev > 0.0) || !std::isfinite(s.time))
    fail("fluid solver: the saved state's time ", s.time, " s and last step ", s.dt_prev, " s are not usable");
  std::vector<char> seen(n, 0);
  for (uint32_t id : s.ids) {
    if (id >= n || seen[id]) fail("fluid solver: the saved state's ids are not a permutation of 0..", n - 1);
    seen[id] = 1;
  }
  adopt(s);
  if (!bodies_.empty()) {
    bodies_.reset(s.bodies, time_);
    sync_body_centres();
  }
  // The particles come in the order the grid sorted them into, and sorting them again keeps it (the
  // sort breaks ties by index), so the grid, pairs and their summation order are the saved run's.
  fluid::place_boundary(boundary_, placements_at(time_), false);
  update_neighbourhoods();
}

FluidFrame FluidSolver::frame(int index) const {
  const fluid::Particles& p = particles_;
  const size_t n = p.size();
  FluidFrame f;
  f.index = index;
  f.time = time_;
  f.positions.resize(n);
  f.velocities.resize(n);
  f.ids.resize(n);
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      f.positions[p.id[i]] = p.x[i];
      f.velocities[p.id[i]] = p.v[i];
      f.ids[i] = uint32_t(i);
    }
  });
  return f;
}

std::vector<float> FluidSolver::density_ratios() const {
  std::vector<float> out(particles_.size());
  for (size_t i = 0; i < out.size(); ++i) out[particles_.id[i]] = particles_.density[i];
  return out;
}

std::vector<Vec3f> FluidSolver::boundary_positions() const {
  std::span<const Vec3f> s = boundary_.grid.sorted_points();
  return {s.begin(), s.end()};
}

FluidSequenceInfo FluidSolver::info(double fps) const {
  FluidSequenceInfo info;
  info.particle_radius = params_.particle_radius;
  info.support_radius = kernel_.h;
  info.fps = fps;
  info.rest_density = params_.rest_density;
  return info;
}

SolverStats FluidSolver::stats() const {
  SolverStats s = stats_;
  const SolverCounters& c = counters_;
  s.time = time_;
  s.steps = c.steps;
  s.min_dt_used = c.min_dt_used;
  s.max_dt_used = c.max_dt_used;
  s.density_error = c.density_error;
  s.max_density_error = c.max_density_error;
  s.divergence_error = c.divergence_error;
  s.density_unconverged = c.density_unconverged;
  s.divergence_unconverged = c.divergence_unconverged;
  s.corrections = c.corrections;
  s.dt_clamped_to_min = c.dt_clamped_to_min;
  s.retries = c.retries;
  s.step_cap = c.step_cap;
  if (c.steps) {
    s.average_dt = c.dt_sum / double(c.steps);
    s.average_density_iterations = double(c.density_iterations) / double(c.steps);
    s.average_divergence_iterations = double(c.divergence_iterations) / double(c.steps);
  }
  return s;
}

}  // namespace spume
