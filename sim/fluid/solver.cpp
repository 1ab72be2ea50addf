#include "solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.h"
#include "core/parallel.h"
#include "fluid/forces.h"
#include "fluid/pressure.h"
#include "fluid/reduce.h"
#include "fluid/time_step.h"

namespace spume {
namespace {

class StageTimer {
 public:
  explicit StageTimer(double& seconds) : seconds_(seconds), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() { seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

 private:
  double& seconds_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

FluidSolver::FluidSolver(FluidSolverParams params, const std::vector<FluidBlock>& blocks, SolidSet solids)
    : params_(params), solids_(std::move(solids)), kernel_(4.0f * params.particle_radius) {
  validate(params_);
  for (size_t s = 0; s < solids_.solids().size(); ++s)
    solids_.solids()[s].motion.validate(str("solid ", s).c_str());
  const float r = params_.particle_radius;
  volume_ = 8.0f * r * r * r;
  dt_prev_ = params_.max_dt;
  const SolidSet now = solids_.at_time(0.0);
  particles_ = fluid::fill_blocks(blocks, r, now, stats_.removed_at_start);
  if (particles_.size() == 0) fail("fluid solver: the fluid blocks hold no particles at radius ", r, " m");
  boundary_ = fluid::sample_boundary(solids_, params_.boundary_spacing * r, kernel_.h);
  fluid::place_boundary(boundary_, solids_, 0.0, true);
  stats_.fluid_particles = particles_.size();
  stats_.boundary_particles = boundary_.size();
  update_neighbourhoods();
}

void FluidSolver::update_neighbourhoods() {
  StageTimer timer(stats_.stage_seconds[size_t(FluidStage::Neighbours)]);
  grid_.build(particles_.x, kernel_.h);
  particles_.reorder(grid_.sorted_to_original());
  fluid::build_neighbourhoods(grid_, boundary_, kernel_, volume_, particles_, neighbourhoods_);
}

void FluidSolver::advance_to(double t) {
  while (time_ < t) step_to(t);
}

double FluidSolver::step() { return step_to(INFINITY); }

double FluidSolver::step_to(double target) {
  auto& seconds = stats_.stage_seconds;
  fluid::Particles& p = particles_;
  const size_t n = p.size();

  // Divergence-free solve at the current positions ([BK17], divergence-free solver). Its result does not depend on
  // dt except through the error measure, so the previous step size is used.
  if (params_.divergence_solve) {
    StageTimer timer(seconds[size_t(FluidStage::Divergence)]);
    const fluid::SolveResult r = fluid::divergence_solve(params_, neighbourhoods_, boundary_, dt_prev_, p);
    divergence_iterations_ += uint64_t(r.iterations);
    stats_.divergence_error = r.error;
    stats_.divergence_unconverged += r.converged ? 0 : 1;
  }

  double dt;
  {
    StageTimer timer(seconds[size_t(FluidStage::Forces)]);
    fluid::non_pressure_accelerations(params_, neighbourhoods_, boundary_, kernel_.h, volume_, dt_prev_, p);
    const fluid::TimeStepChoice choice = fluid::cfl_time_step(params_, p, dt_prev_, solids_, time_);
    stats_.dt_clamped_to_min += choice.clamped_to_min ? 1 : 0;
    dt = fluid::fit_to_remaining(choice.dt, target - time_);
  }
  const double t_end = dt == target - time_ ? target : time_ + dt;

  // Predict velocities, then make the density after this step rho0 ([BK17], constant-density solver).
  {
    StageTimer timer(seconds[size_t(FluidStage::Density)]);
    const float fdt = float(dt);
    parallel_for(n, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) p.v[i] += fdt * p.accel[i];
    });
    fluid::set_boundary_step_velocity(boundary_, solids_, time_, t_end);
    const fluid::SolveResult r = fluid::density_solve(params_, neighbourhoods_, boundary_, dt, p);
    density_iterations_ += uint64_t(r.iterations);
    stats_.density_error = r.error;
    stats_.max_density_error = std::max(stats_.max_density_error, r.error);
    stats_.density_unconverged += r.converged ? 0 : 1;
  }

  // Advect, move the solids, and keep every particle in free space.
  {
    StageTimer timer(seconds[size_t(FluidStage::Advect)]);
    const float fdt = float(dt);
    parallel_for(n, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) p.x[i] += fdt * p.v[i];
    });
    time_ = t_end;
    fluid::place_boundary(boundary_, solids_, time_, false);
    project_out_of_solids();
  }

  dt_prev_ = dt;
  ++stats_.steps;
  dt_sum_ += dt;
  stats_.min_dt_used = stats_.steps == 1 ? dt : std::min(stats_.min_dt_used, dt);
  stats_.max_dt_used = std::max(stats_.max_dt_used, dt);
  update_neighbourhoods();
  return dt;
}

void FluidSolver::project_out_of_solids() {
  fluid::Particles& p = particles_;
  const size_t n = p.size();
  const SolidSet now = solids_.at_time(time_);
  const float skin = params_.push_out_skin * params_.particle_radius;
  // Counts are exact integers in double, so the sum is thread-independent anyway.
  const double bad = fluid::chunked_sum(n, [&](size_t b, size_t e) {
    double count = 0.0;
    for (size_t i = b; i < e; ++i) count += finite(p.x[i]) && finite(p.v[i]) ? 0.0 : 1.0;
    return count;
  });
  if (bad > 0.0)
    for (size_t i = 0; i < n; ++i)
      if (!finite(p.x[i]) || !finite(p.v[i]))
        fail("fluid solver: particle ", p.id[i], " has a non-finite position or velocity at t = ", time_,
             " s (", uint64_t(bad), " particles in all); try a smaller max_dt or cfl");
  if (now.empty()) return;
  const double moved = fluid::chunked_sum(n, [&](size_t b, size_t e) {
    double count = 0.0;
    for (size_t i = b; i < e; ++i) count += now.push_out(p.x[i], p.v[i], skin) ? 1.0 : 0.0;
    return count;
  });
  stats_.corrections += uint64_t(moved);
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
  s.time = time_;
  if (s.steps) {
    s.average_dt = dt_sum_ / double(s.steps);
    s.average_density_iterations = double(density_iterations_) / double(s.steps);
    s.average_divergence_iterations = double(divergence_iterations_) / double(s.steps);
  }
  return s;
}

}  // namespace spume
