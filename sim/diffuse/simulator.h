#pragma once
// The diffuse simulator: a post-process that steps diffuse particles through a fluid sequence.
// Per step (MODEL.md): the fluid at t prepared (FLIP velocities and density, a narrow band filled: §9)
// -> neighbour grid over it -> classify every diffuse particle and
// sample the fluid velocity at it (§3, §4) -> formation potentials and emission (§1, §2) -> advection
// per type, solids, domain, dissolution (§4, §5, §8) -> compaction in cell order.
#include <array>
#include <string>
#include <functional>

#include "sim/core/frames.h"
#include "sim/core/memory_room.h"
#include "sim/core/unusable_masses.h"
#include "sim/diffuse/emission.h"
#include "sim/diffuse/fluid_sampling.h"
#include "sim/diffuse/flip_fluid.h"
#include "sim/diffuse/fluid_state.h"
#include "sim/diffuse/narrow_band.h"
#include "sim/diffuse/params.h"
#include "sim/diffuse/potentials.h"
#include "sim/grid/neighbour_grid.h"
#include "sim/geometry/body_track.h"
#include "sim/geometry/solid_clearance.h"

namespace spume {

// What the diffuse stage holds a particle at its peak, everything included (its state, the fluid
// samples, the compaction, the cache encoder and its pool, the last frame's restart): 155 bytes over
// the whole process at 106M particles (tests/bench/RESULTS.md, "One hundred million particles from a
// real flow"), rounded up.
constexpr double kDiffuseStageBytesPerParticle = 160.0;

enum class Stage { Grid, Classify, Potentials, Emit, Advect, Count };
constexpr std::array<const char*, size_t(Stage::Count)> kStageNames = {"grid", "classify", "potentials", "emit",
                                                                         "advect"};

// What happened between the previous frame and this one, and what exists at this frame.
struct FrameStats {
  int frame = 0;
  size_t fluid = 0;
  std::array<size_t, kDiffuseTypeCount> by_type{};  // spray, foam, bubbles at this frame
  uint64_t generated = 0;   // emitted since the previous frame
  uint64_t dissolved = 0;   // foam whose lifetime ran out since the previous frame
  uint64_t removed = 0;     // left the domain since the previous frame
  uint64_t landed = 0;      // ... of them, below the ground (thrown over a tank's rim, fallen outside it)
  uint64_t dropped = 0;     // candidates the emission budget refused since the previous frame
  uint64_t capped = 0;      // asked for by Eq. 8 beyond 4,095 per fluid particle and step, never sampled
  std::array<double, size_t(Stage::Count)> stage_ms{};
  std::string unpaired_because;  // why this frame's particles were not paired with the next's ("" if paired)
  InteriorFill interior;         // this frame's narrow-band test and fill (MODEL.md §9.1)
  float density_ratio = 1.0f;    // fluid.particles = flip: this frame's particle density / the nominal (§9.2)
  float full_count = 0.0f;       // ... the count of a full neighbourhood it was measured from
  UnusableMasses unusable_masses;  // masses of 0 or less in the fluid frame, weighed with the uniform mass
};

// What the cached particles are (fluid.particles).
enum class FluidParticles { Sph, Flip };

struct DiffuseSetup {
  DiffuseParams params;
  FluidSequenceInfo fluid;
  SolidSet solids;
  BodyTrack bodies;  // poses of the dynamic solids (empty: they stay at their initial pose)
  Aabb domain;  // diffuse particles outside are deleted; empty box = no limit
  std::optional<GroundPlane> ground;  // where spray over a tank's rim lands (SolidSet::ground_below_tanks)
  FluidParticles particles = FluidParticles::Sph;  // flip: smoothed velocities, counts at the frame's density
  bool fill_narrow_band = true;                    // fluid.narrow_band = auto: fill an enclosed empty interior
  MemoryRoom::Available available_memory = available_memory_bytes;  // what a step may grow into
};

class DiffuseSimulator {
 public:
  explicit DiffuseSimulator(DiffuseSetup setup);

  // Classifies the diffuse particles against fluid frame `a` and hands them to `frame_ready` (frame a's
  // output: positions at a's time, types from a's fluid), then steps them to the time of `b`. With
  // b == nullptr (the last frame) it only classifies. Returns frame a's statistics. Running out of
  // memory is an Error saying how many particles it was simulating.
  FrameStats process_frame(const FluidFrame& a, const FluidFrame* b,
                           const std::function<void(const DiffuseFrame&, const FrameStats&)>& frame_ready);

  const DiffuseFrame& particles() const { return particles_; }
  // Bytes the step's working arrays hold (fluid samples, sort, compaction): about 58 a diffuse
  // particle between steps, none after a last frame (process_frame with b == nullptr).
  size_t step_scratch_bytes() const;
  // Resume from a stored state (e.g. a diffuse cache of frame k, then process_frame(k, k+1)).
  void set_particles(DiffuseFrame particles);
  const DiffuseSetup& setup() const { return setup_; }

 private:
  // process_frame's work; process_frame says what it was doing when memory ran out.
  FrameStats simulate_frame(const FluidFrame& a, const FluidFrame* b,
                            const std::function<void(const DiffuseFrame&, const FrameStats&)>& frame_ready);
  // classify(): grid over the fluid at t, neighbour counts and fluid velocities at every diffuse
  // particle, types (with the solids as they stand at t). step(): advection, solids at t + dt,
  // dissolution, emission, compaction over [t, t + dt].
  void classify(const FluidStepState& state, uint32_t step, bool sample_velocity, double t);
  // Frees the step's working arrays: after a last frame nothing steps, and the caches' encoders
  // (the restart's 2.5 GB at 106M particles) then take that memory instead of adding to the peak.
  void release_step_scratch();
  // After each interpolation: FLIP velocities and density (§9.2), the narrow band's fill (§9.1), and
  // the parameters of this step. `frame_start`: the state is a frame as read (the band is decided there).
  void prepare_fluid(double t, bool frame_start);
  void step(const FluidStepState& state, uint32_t step, float dt, double t_end);
  // The solids at time t: the set as given when nothing moves, else a snapshot kept in `slot`.
  const SolidSet& solids_at(double t, SolidSet& slot) const;
  // Where `solids` (from solids_at) leave particles alone, within the support radius: built once when
  // nothing moves, else for every snapshot.
  const SolidClearance& clearance_of(const SolidSet& solids, SolidClearance& slot);

  DiffuseSetup setup_;
  DiffuseFrame particles_;
  NeighbourGrid grid_;
  FluidStepState state_;
  std::vector<Vec3f> sorted_motion_;
  // The step's working arrays, reused every step (fresh memory costs a page fault per 4 KiB), and
  // freed as one after a last frame.
  struct StepScratch {
    FluidSamples samples;
    std::vector<uint8_t> alive;  // 1 alive, 0 dissolved, 2 left the domain
    std::vector<uint32_t> order;
    std::vector<uint64_t> compaction_ids;      // the old ids after a compaction (compaction.h)
    std::vector<DiffuseType> compaction_types;  // the old types likewise
    size_t bytes() const;
  };
  StepScratch scratch_;
  FormationPotentials potentials_;
  EmissionBuffers emission_buffers_;
  SolidSet classify_solids_, step_solids_;
  SolidClearance classify_clearance_, step_clearance_;
  FrameStats pending_;  // accumulates between frames
  MemoryRoom room_;     // refuses a step whose newborns cannot fit
  const SolidSet* solids_now_ = nullptr;  // the solids at the time of the last classify()
  float particle_volume_;
  FlipFluid flip_;
  InteriorFiller filler_;
  InteriorFill band_;            // the current frame's narrow-band test (§9.1)
  DiffuseParams step_params_;   // setup_.params, at the frame's density for a FLIP cache
  float step_volume_ = 0.0f;    // particle_volume_, likewise
};

}  // namespace spume
