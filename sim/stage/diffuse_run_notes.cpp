#include "sim/stage/diffuse_run_notes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/core/error.h"
#include "sim/core/messages.h"
#include "sim/diffuse/narrow_band.h"

namespace spume {

DiffuseRunNotes::DiffuseRunNotes(const SimScene& scene, Progress& progress, size_t frames, bool solids)
    : scene_(scene), progress_(progress), frames_(frames), solids_(solids) {}

void DiffuseRunNotes::written(const FrameStats& stats, int frame) {
  if (stats.dropped > 0 && !warned_budget_) {
    messages::warning(str("the emission budget diffuse.max_particles = ", *scene_.diffuse.max_particles,
                          " binds from frame ", frame,
                          ": emission is thinned uniformly at random (unbiased in space); see stats.csv 'dropped'"));
    warned_budget_ = true;
  }
  if (stats.capped > 0 && !warned_cap_) {
    messages::warning(str("from frame ", frame, " Eq. 8 asks some fluid particles for more than ", kMaxSamplesPerStep,
                          " new diffuse particles in one step, the most a diffuse id can number; ", stats.capped,
                          " were not emitted in this frame (stats.csv 'capped' counts every frame). More "
                          "diffuse.substeps or lower diffuse.k_ta / diffuse.k_wc avoid it"));
    warned_cap_ = true;
  }
}

void DiffuseRunNotes::interior(const FrameStats& stats) {
  if (stats.interior.narrow_band) {
    most_filled_ = std::max(most_filled_, stats.interior.filled);
    if (++band_frames_ == 1)
      progress_.note(str("frame ", stats.frame, "'s interior: ", describe_interior(stats.interior), "; filled with ",
                         stats.interior.filled, " massless particles for classification and advection "
                         "(MODEL.md §9.1; fluid.narrow_band = off leaves it empty)"));
  } else if (stats.interior.large && !noted_pocket_) {
    progress_.note(str("note: frame ", stats.frame, "'s interior: ", describe_interior(stats.interior), " (MODEL.md §9.1)"));
    noted_pocket_ = true;
  }
  if (stats.interior.skipped && !warned_band_skip_) {
    progress_.note(str("note: frame ", stats.frame, "'s particles spread over more than 16M cells of h; "
                       "such frames are not tested for an empty interior (MODEL.md §9.1)"));
    warned_band_skip_ = true;
  }
}

void DiffuseRunNotes::flip_density(const FrameStats& stats, bool first) {
  if (!scene_.flip_particles) return;
  if (first) {
    const double nominal = 4.0 / 3.0 * std::numbers::pi *
                           std::pow(double(scene_.fluid.support_radius) / (2.0 * scene_.fluid.particle_radius), 3.0);
    progress_.note(str("fluid.particles = flip: velocities averaged over ", kVelocitySmoothing, " h for the "
                       "potentials; frame ", stats.frame, " holds ", stats.full_count, " particles in a full "
                       "neighbourhood (", stats.density_ratio, "x the nominal ", nominal, " at a spacing of 2r), "
                       "counts and rates taken at that density (MODEL.md §9.2)"));
  }
  least_density_ = first ? stats.density_ratio : std::min(least_density_, stats.density_ratio);
  most_density_ = std::max(most_density_, stats.density_ratio);
}

void DiffuseRunNotes::simulated(const FrameStats& stats, bool first, int next_frame, bool has_velocities) {
  interior(stats);
  flip_density(stats, first);
  if (stats.unusable_masses.count > 0 && !warned_masses_) {
    messages::warning(str("frame ", stats.frame, ": ", stats.unusable_masses.describe(stats.fluid),
                          " (Houdini writes -1 where no mass was set): those particles take the uniform mass "
                          "rho0 (2r)^3 = ", scene_.fluid.uniform_mass(), " kg for their kinetic energy"));
    warned_masses_ = true;
  }
  if (!stats.unpaired_because.empty() && ++unpaired_frames_ == 1)
    messages::warning(str("the fluid frames carry no particle ids, and from frame ", stats.frame, " to ", next_frame,
                          " ", stats.unpaired_because, ": particles are not paired by index there; ",
                          has_velocities ? "each moves with its stored velocity between frames"
                                         : "without stored velocities they stand still between frames, "
                                           "so foam and bubbles are not carried by the flow",
                          " (MODEL.md §8.16; a cache with an id attribute avoids it)"));
  // Spray that fell over a tank's rim to the ground is where it belongs; the rest may be a domain
  // drawn too tight.
  landed_ += stats.landed;
  const uint64_t lost = stats.removed - stats.landed;
  if (stats.generated > 0 && lost * 100 > stats.generated) {
    if (++domain_warnings_ <= 3)
      messages::warning(str("frame ", stats.frame, " removed ", lost, " diffuse particles outside the "
                            "domain, ", 100.0 * double(lost) / double(stats.generated), "% of the ",
                            stats.generated, " emitted; ",
                            solids_ ? "if the flow reaches beyond the domain, widen domain.min / domain.max"
                                    : "the run has no container (none given, none inferred: the log says why), so "
                                      "spray falls through where the floor is; give it (--tank X0,Y0,Z0,X1,Y1,Z1 or "
                                      "solids), or widen domain.min / domain.max"));
    if (domain_warnings_ == 3)
      messages::warning("more frames may lose diffuse particles to the domain: stats.csv counts them, column removed");
  }
}

void DiffuseRunNotes::finish() const {
  if (band_frames_ > 0)
    progress_.note(str("  (", band_frames_, " of ", frames_, " frames were a narrow band, filled with up to ",
                       most_filled_, " particles)"));
  if (landed_ > 0)
    progress_.note(str("  (", landed_, " diffuse particles were thrown over a tank's rim and deleted when they "
                       "reached the ground beside it; stats.csv's landed counts them)"));
  if (scene_.flip_particles)
    progress_.note(str("  (fluid.particles = flip: particle density ", least_density_, " to ", most_density_,
                       "x the nominal over the frames)"));
  if (unpaired_frames_ > 1)
    messages::warning(str(unpaired_frames_, " of ", frames_ - 1, " frame intervals left their particles unpaired "
                          "(fluid frames without ids)"));
}

}  // namespace spume
