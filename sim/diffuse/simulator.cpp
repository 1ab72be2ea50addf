#include "simulator.h"

#include <chrono>

#include "core/error.h"
#include "core/parallel.h"
#include "diffuse/advection.h"
#include "diffuse/emission.h"

namespace spume {
namespace {

class StageTimer {
 public:
  StageTimer(FrameStats& stats, Stage stage) : stats_(stats), stage_(stage), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() {
    stats_.stage_ms[size_t(stage_)] +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  FrameStats& stats_;
  Stage stage_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

DiffuseSimulator::DiffuseSimulator(DiffuseSetup setup) : setup_(std::move(setup)) {
  const float r = setup_.fluid.particle_radius;
  particle_volume_ = 8.0f * r * r * r;  // spacing 2r
  rest_number_density_ = 1.0f / particle_volume_;
}

void DiffuseSimulator::classify(const FluidStepState& state, uint32_t step, bool sample_velocity) {
  {
    StageTimer t(pending_, Stage::Grid);
    grid_.build(state.positions, setup_.fluid.support_radius);
    const auto order = grid_.sorted_to_original();
    sorted_motion_.assign(order.size(), Vec3f::Zero());
    if (sample_velocity)
      parallel_for(order.size(), 4096, [&](size_t b, size_t e) {
        for (size_t j = b; j < e; ++j) sorted_motion_[j] = state.motion[order[j]];
      });
  }
  StageTimer t(pending_, Stage::Classify);
  sample_fluid(grid_, sorted_motion_, particles_.positions, samples_);
  const DiffuseParams& p = setup_.params;
  const bool solids = p.count_solids && !setup_.solids.empty();
  const float h = setup_.fluid.support_radius;
  parallel_for(particles_.size(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      float count = samples_.neighbour_count[i];
      if (solids) count += rest_number_density_ * setup_.solids.solid_volume_within(particles_.positions[i], h);
      samples_.neighbour_count[i] = count;
      // Particles born in the previous step have no type yet: no hysteresis for them.
      const bool newborn = diffuse_id_step(particles_.ids[i]) == ((step - 1) & kMaxBirthStep);
      particles_.types[i] = spume::classify(count, p, newborn ? nullptr : &particles_.types[i]);
    }
  });
}

void DiffuseSimulator::step(const FluidStepState& state, uint32_t step, float dt) {
  const DiffuseParams& p = setup_.params;
  const size_t old_count = particles_.size();

  // Advect the existing particles (MODEL.md §4), keep them out of solids, dissolve foam (§5).
  std::vector<uint8_t> alive(old_count, 1);
  {
    StageTimer t(pending_, Stage::Advect);
    const float skin = 1e-4f * setup_.fluid.particle_radius;
    const bool limit = !setup_.domain.empty();
    parallel_for(old_count, 4096, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) {
        Vec3f& x = particles_.positions[i];
        Vec3f& v = particles_.velocities[i];
        // Where no fluid is within h there is no fluid velocity to follow: keep the particle's own.
        const Vec3f u = samples_.kernel_sum[i] > 0.0f ? samples_.fluid_velocity[i] : v;
        switch (particles_.types[i]) {
          case DiffuseType::Spray: advance_spray(x, v, p.gravity, dt, p.spray_integrator); break;
          case DiffuseType::Foam:
            advance_foam(x, v, u, dt, p.foam_velocity);
            particles_.lifetimes[i] -= dt;
            if (particles_.lifetimes[i] <= 0.0f) alive[i] = 0;
            break;
          case DiffuseType::Bubble: advance_bubble(x, v, u, p, dt); break;
        }
        setup_.solids.push_out(x, v, skin);
        if (alive[i] && limit && !setup_.domain.contains(x)) alive[i] = 2;
      }
    });
  }

  // Emit from the fluid at t (MODEL.md §1-2); newborns are appended after the existing particles.
  EmissionResult emitted;
  if (p.k_ta > 0.0f || p.k_wc > 0.0f) {
    {
      StageTimer t(pending_, Stage::Potentials);
      compute_potentials(grid_, state, p, particle_volume_, potentials_);
    }
    StageTimer t(pending_, Stage::Emit);
    // The budget counts the particles that survive this step.
    size_t survivors = 0;
    for (uint8_t a : alive) survivors += a == 1;
    DiffuseParams budget = p;
    if (p.max_particles) budget.max_particles = *p.max_particles + (old_count - survivors);
    emitted = emit_diffuse(state, potentials_, budget, step, dt, setup_.fluid.particle_radius, particles_);
  }
  // A newborn sampled around a fluid particle that hugs a wall may start inside it.
  if (!setup_.solids.empty()) {
    const float skin = 1e-4f * setup_.fluid.particle_radius;
    parallel_for(particles_.size() - old_count, 4096, [&](size_t b, size_t e) {
      for (size_t k = old_count + b; k < old_count + e; ++k)
        setup_.solids.push_out(particles_.positions[k], particles_.velocities[k], skin);
    });
  }
  pending_.generated += emitted.emitted;
  pending_.dropped += emitted.requested - emitted.emitted;

  // Compact: survivors in cell order (spatially coherent for the next step), then the newborns.
  StageTimer t(pending_, Stage::Advect);
  std::vector<uint32_t> order;
  order.reserve(particles_.size());
  for (uint32_t i : samples_.cell_order) {
    if (alive[i] == 1) order.push_back(i);
    else if (alive[i] == 0) ++pending_.dissolved;
    else ++pending_.removed;
  }
  for (size_t i = old_count; i < particles_.size(); ++i) {
    if (setup_.domain.empty() || setup_.domain.contains(particles_.positions[i])) order.push_back(uint32_t(i));
    else ++pending_.removed;
  }
  DiffuseFrame next;
  next.index = particles_.index;
  next.time = particles_.time;
  next.resize(order.size());
  parallel_for(order.size(), 1 << 14, [&](size_t b, size_t e) {
    for (size_t k = b; k < e; ++k) {
      const uint32_t i = order[k];
      next.ids[k] = particles_.ids[i];
      next.positions[k] = particles_.positions[i];
      next.velocities[k] = particles_.velocities[i];
      next.lifetimes[k] = particles_.lifetimes[i];
      next.types[k] = particles_.types[i];
    }
  });
  particles_ = std::move(next);
}

FrameStats DiffuseSimulator::process_frame(const FluidFrame& a, const FluidFrame* b,
                                           const std::function<void(const DiffuseFrame&, const FrameStats&)>& ready) {
  const DiffuseParams& p = setup_.params;
  if (a.index < 0) fail("frame ", a.index, ": frame numbers must be >= 0");
  const uint64_t first_step = uint64_t(a.index) * uint64_t(p.substeps);
  if (first_step + p.substeps > kMaxBirthStep)
    fail("frame ", a.index, ": with ", p.substeps, " substeps this passes step ", kMaxBirthStep,
         ", the most a diffuse id can record; use fewer frames or substeps");
  const double frame_dt = b ? b->time - a.time : 0.0;
  if (b && !(frame_dt > 0.0))
    fail("frames ", a.index, " and ", b->index, ": times ", a.time, " and ", b->time, " do not increase");

  const FramePair pair = pair_frames(a, b, frame_dt);
  const float mass = setup_.fluid.uniform_mass();

  // Frame a's output: the particles where they are, classified against a's fluid.
  interpolate_fluid(pair, 0.0f, mass, state_);
  classify(state_, uint32_t(first_step), b != nullptr);
  particles_.index = a.index;
  particles_.time = a.time;
  pending_.frame = a.index;
  pending_.fluid = a.size();
  pending_.by_type = particles_.count_by_type();
  ready(particles_, pending_);
  const FrameStats done = pending_;
  pending_ = FrameStats{};
  if (!b) return done;

  // Step to b; the work is reported with frame b.
  const float dt = float(frame_dt / p.substeps);
  for (int s = 0; s < p.substeps; ++s) {
    const uint32_t step_index = uint32_t(first_step + s);
    if (s > 0) {
      interpolate_fluid(pair, float(s) / float(p.substeps), mass, state_);
      classify(state_, step_index, true);
    }
    step(state_, step_index, dt);
  }
  particles_.time = b->time;
  return done;
}

}  // namespace spume
