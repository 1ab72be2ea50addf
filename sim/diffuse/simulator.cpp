#include "sim/diffuse/simulator.h"

#include <atomic>
#include <cmath>

#include "sim/core/error.h"
#include "sim/core/huge_pages.h"
#include "sim/core/out_of_memory.h"
#include "sim/core/parallel.h"
#include "sim/core/stopwatch.h"
#include "sim/diffuse/advection.h"
#include "sim/diffuse/compaction.h"
#include "sim/diffuse/emission.h"
#include "sim/geometry/solid_coverage.h"

namespace spume {
namespace {

// Adds the wall-clock time of its scope to a stage's total.
class StageTimer {
 public:
  StageTimer(FrameStats& stats, Stage stage) : stats_(stats), stage_(stage) {}
  ~StageTimer() { stats_.stage_ms[size_t(stage_)] += watch_.milliseconds(); }

 private:
  FrameStats& stats_;
  Stage stage_;
  Stopwatch watch_;
};

}  // namespace

DiffuseSimulator::DiffuseSimulator(DiffuseSetup setup)
    : setup_(std::move(setup)),
      room_("the diffuse stage", "diffuse particles", kDiffuseStageBytesPerParticle,
            "lower the emission (diffuse.k_ta, diffuse.k_wc), shorten diffuse.lifetime, cap the count with "
            "diffuse.max_particles, or run on a machine with more memory",
            setup_.available_memory) {
  const float r = setup_.fluid.particle_radius;
  particle_volume_ = 8.0f * r * r * r;  // spacing 2r
}

void DiffuseSimulator::set_particles(DiffuseFrame particles) {
  // Held from now on: the step's check counts only what the stage adds to them.
  constexpr size_t kParticleBytes = sizeof(uint64_t) + 2 * sizeof(Vec3f) + sizeof(float) + sizeof(DiffuseType);
  room_.holding(double(particles.size()) * kParticleBytes);
  particles_ = std::move(particles);
}

const SolidSet& DiffuseSimulator::solids_at(double t, SolidSet& slot) const {
  if (!setup_.solids.any_moving()) return setup_.solids;
  slot = solids_at_time(setup_.solids, setup_.bodies, t);
  return slot;
}

const SolidClearance& DiffuseSimulator::clearance_of(const SolidSet& solids, SolidClearance& slot) {
  if (!slot.built() || setup_.solids.any_moving()) slot = SolidClearance(solids, setup_.fluid.support_radius);
  return slot;
}

void DiffuseSimulator::prepare_fluid(double t, bool frame_start) {
  StageTimer timer(pending_, Stage::Grid);  // fluid preparation, reported with the grid
  step_params_ = setup_.params;
  step_volume_ = particle_volume_;
  float ratio = 1.0f;
  if (setup_.particles == FluidParticles::Flip) {
    const FlipMeasure m = flip_.prepare(state_, setup_.fluid.particle_radius, setup_.fluid.support_radius);
    ratio = m.density_ratio;
    step_params_ = at_density(setup_.params, ratio);
    step_volume_ = particle_volume_ / ratio;
    pending_.density_ratio = ratio, pending_.full_count = m.full_count;
  }
  if (!setup_.fill_narrow_band) return;
  // Decided once a frame, on the frame's particles as read (no solids) and on cells of h, as `spume
  // info` decides on the file; the frame's steps are filled alike.
  if (frame_start)
    band_ = filler_.examine(state_.positions, setup_.fluid.support_radius, setup_.params.gravity,
                            setup_.particles == FluidParticles::Flip);
  if (band_.narrow_band) {
    // Fill at the frame's own spacing (2r, or the measured one of a FLIP cache).
    const float spacing = 2.0f * setup_.fluid.particle_radius / std::cbrt(ratio);
    const SolidSet& solids = solids_at(t, classify_solids_);
    const size_t filled = filler_.fill(state_, band_.cell, spacing, setup_.params.gravity, &solids);
    if (frame_start) band_.filled = filled;
  }
  if (frame_start) pending_.interior = band_;
}

void DiffuseSimulator::classify(const FluidStepState& state, uint32_t step, bool sample_velocity, double t) {
  {
    StageTimer timer(pending_, Stage::Grid);
    grid_.build(state.positions, setup_.fluid.support_radius);
    const auto order = grid_.sorted_to_original();
    resize_discarding_in_huge_pages(sorted_motion_, order.size());
    parallel_for(order.size(), 4096, [&](size_t b, size_t e) {
      for (size_t j = b; j < e; ++j) sorted_motion_[j] = sample_velocity ? state.motion[order[j]] : Vec3f::Zero();
    });
  }
  StageTimer timer(pending_, Stage::Classify);
  sample_fluid(grid_, sorted_motion_, particles_.positions, scratch_.samples);
  const DiffuseParams& p = step_params_;
  const SolidSet& solids = solids_at(t, classify_solids_);
  solids_now_ = &solids;
  const bool count_solids = p.count_solids && !solids.empty();
  const float h = setup_.fluid.support_radius;
  const SolidClearance* clearance = count_solids ? &clearance_of(solids, classify_clearance_) : nullptr;
  parallel_for(particles_.size(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      float count = scratch_.samples.neighbour_count[i];
      // Particles born in the previous step have no type yet: no hysteresis for them.
      const bool newborn = diffuse_id_step(particles_.ids[i]) == ((step - 1) & kMaxBirthStep);
      const DiffuseType* previous = newborn ? nullptr : &particles_.types[i];
      // A wall counts as the water it replaces only as far as the wall is wet (MODEL.md §8.11): a
      // dry wall adds nothing, a submerged floor a full neighbourhood, the waterline about half.
      // The type only grows with the count, so where both bounds on the covered share give the same
      // type the exact share is not needed (most particles near a box's edges).
      if (count_solids && count > 0.0f && !clearance->clear(particles_.positions[i])) {
        const Vec3f& x = particles_.positions[i];
        const CoverageBounds bounds = solid_coverage_bounds(solids, x, h);
        const float low = wet_wall_count(count, bounds.lo);
        if (bounds.lo == bounds.hi || spume::classify(low, p, previous) ==
                                          spume::classify(wet_wall_count(count, bounds.hi), p, previous))
          count = low;
        else
          count = wet_wall_count(count, solid_coverage(solids, x, h, false).fraction);
      }
      scratch_.samples.neighbour_count[i] = count;
      particles_.types[i] = spume::classify(count, p, previous);
    }
  });
}

void DiffuseSimulator::step(const FluidStepState& state, uint32_t step, float dt, double t_end) {
  const DiffuseParams& p = step_params_;
  const size_t old_count = particles_.size();
  // Positions after the step belong to t_end: keep them out of the solids as they stand then,
  // relative to each wall's velocity then.
  const SolidSet& solids = solids_at(t_end, step_solids_);
  const float skin = 1e-4f * setup_.fluid.particle_radius;
  const bool limit = !setup_.domain.empty();
  const SolidClearance& clearance = clearance_of(solids, step_clearance_);

  // Advect the existing particles (MODEL.md §4), keep them out of solids, dissolve foam (§5).
  resize_discarding_in_huge_pages(scratch_.alive, old_count);
  std::atomic<uint64_t> dissolved{0}, removed{0}, landed{0};
  {
    StageTimer timer(pending_, Stage::Advect);
    const BubbleStep bubble = bubble_step(p, dt);
    parallel_for(old_count, 4096, [&](size_t b, size_t e) {
      uint64_t dissolved_here = 0, removed_here = 0, landed_here = 0;
      for (size_t i = b; i < e; ++i) {
        Vec3f& x = particles_.positions[i];
        Vec3f& v = particles_.velocities[i];
        uint8_t alive = 1;
        // Where no fluid is within h there is no fluid velocity to follow: keep the particle's own.
        const Vec3f u = scratch_.samples.kernel_sum[i] > 0.0f ? scratch_.samples.fluid_velocity[i] : v;
        const Vec3f from = x;
        switch (particles_.types[i]) {
          case DiffuseType::Spray: advance_spray(x, v, p.gravity, dt, p.spray_integrator); break;
          case DiffuseType::Foam:
            advance_foam(x, v, u, dt, p.foam_velocity);
            particles_.lifetimes[i] -= dt;
            if (particles_.lifetimes[i] <= 0.0f) alive = 0;
            break;
          case DiffuseType::Bubble: advance_bubble(x, v, u, bubble); break;
        }
        // Ending where no solid is near, a step crossed no tank wall (it ends inside them all).
        if (!clearance.clear(x)) {
          solids.stop_at_tank_walls(from, x, v, skin);
          solids.push_out(x, v, skin);
        }
        if (alive && limit && !setup_.domain.contains(x)) alive = 2;
        scratch_.alive[i] = alive;
        dissolved_here += alive == 0, removed_here += alive == 2;
        landed_here += alive == 2 && setup_.ground && x[setup_.ground->up_axis] < setup_.ground->level;
      }
      dissolved += dissolved_here, removed += removed_here, landed += landed_here;
    });
  }
  pending_.dissolved += dissolved;
  pending_.removed += removed;
  pending_.landed += landed;

  // Emit from the fluid at t (MODEL.md §1-2); newborns are appended after the existing particles.
  EmissionResult emitted;
  if (p.k_ta > 0.0f || p.k_wc > 0.0f) {
    {
      StageTimer timer(pending_, Stage::Potentials);
      compute_potentials(grid_, state, p, step_volume_, solids_now_, potentials_);
    }
    StageTimer timer(pending_, Stage::Emit);
    // The budget counts the particles that survive this step.
    const size_t survivors = old_count - size_t(dissolved + removed);
    DiffuseParams budget = p;
    if (p.max_particles) budget.max_particles = *p.max_particles + (old_count - survivors);
    emitted = emit_diffuse(state, potentials_, budget, step, dt, setup_.fluid.particle_radius, particles_,
                           emission_buffers_);
    // A newborn's cylinder around a fluid particle beside a wall may reach into or through it (along
    // the particle's motion, into the floor where a jet lands): it stops at the wall on its fluid
    // particle's side. push_out alone would send one deeper than half a tank wall's thickness outside.
    if (!solids.empty())
      parallel_for(particles_.size() - old_count, 4096, [&](size_t b, size_t e) {
        for (size_t k = old_count + b; k < old_count + e; ++k) {
          Vec3f& x = particles_.positions[k];
          if (clearance.clear(x)) continue;
          solids.stop_at_tank_walls(state.positions[emission_buffers_.parents[k - old_count]], x,
                                    particles_.velocities[k], skin);
          solids.push_out(x, particles_.velocities[k], skin);
        }
      });
  }
  room_.check(particles_.size(), "");  // the stage names the frame
  pending_.generated += emitted.emitted;
  pending_.dropped += emitted.requested - emitted.emitted;
  pending_.capped = pending_.capped > UINT64_MAX - emitted.capped ? UINT64_MAX : pending_.capped + emitted.capped;

  // Compact: survivors in cell order (spatially coherent for the next step), then the newborns.
  StageTimer timer(pending_, Stage::Advect);
  const size_t born = particles_.size() - old_count;
  resize_discarding_in_huge_pages(scratch_.order, particles_.size());
  const std::vector<uint32_t>& cell_order = scratch_.samples.cell_order;
  const size_t survivors = parallel_select(
      old_count, [&](size_t s) { return scratch_.alive[cell_order[s]] == 1; },
      [&](size_t s, size_t k) { scratch_.order[k] = cell_order[s]; });
  const size_t kept_born = parallel_select(
      born, [&](size_t k) { return !limit || setup_.domain.contains(particles_.positions[old_count + k]); },
      [&](size_t k, size_t slot) { scratch_.order[survivors + slot] = uint32_t(old_count + k); });
  pending_.removed += born - kept_born;
  // Reordered in place, column by column. The fluid samples' velocities and kernel sums lend their
  // buffers: advection was their last reader, and the next classify() writes them whole.
  compact(particles_, std::span(scratch_.order).first(survivors + kept_born),
          {scratch_.samples.fluid_velocity, scratch_.samples.kernel_sum, scratch_.compaction_ids,
           scratch_.compaction_types});
}

FrameStats DiffuseSimulator::process_frame(const FluidFrame& a, const FluidFrame* b,
                                           const std::function<void(const DiffuseFrame&, const FrameStats&)>& ready) {
  return allocating(str("simulating ", a.size(), " fluid and ", particles_.size(), " diffuse particles"), 0,
                    [&] { return simulate_frame(a, b, ready); });
}

FrameStats DiffuseSimulator::simulate_frame(const FluidFrame& a, const FluidFrame* b,
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
  prepare_fluid(a.time, true);
  classify(state_, uint32_t(first_step), b != nullptr, a.time);
  particles_.index = a.index;
  particles_.time = a.time;
  pending_.frame = a.index;
  pending_.fluid = a.size();
  pending_.by_type = particles_.count_by_type();
  pending_.unpaired_because = pair.unpaired_because;
  pending_.unusable_masses = unusable_masses(a.masses);
  if (!b) release_step_scratch();  // classified: nothing steps after a last frame
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
      const double t = a.time + frame_dt * s / p.substeps;
      prepare_fluid(t, false);
      classify(state_, step_index, true, t);
    }
    step(state_, step_index, dt, s + 1 == p.substeps ? b->time : a.time + frame_dt * (s + 1) / p.substeps);
  }
  particles_.time = b->time;
  return done;
}

void DiffuseSimulator::release_step_scratch() { scratch_ = StepScratch{}; }

size_t DiffuseSimulator::step_scratch_bytes() const { return scratch_.bytes(); }

size_t DiffuseSimulator::StepScratch::bytes() const {
  return samples.bytes() + held_bytes(alive) + held_bytes(order) + held_bytes(compaction_ids) +
         held_bytes(compaction_types);
}

}  // namespace spume
