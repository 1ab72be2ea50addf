#pragma once
// What the diffuse stage tells the user about its frames as they pass: each condition once, when it
// first appears (a binding emission budget, capped samples, a narrow band, an air pocket, the FLIP
// density, unusable masses, unpaired frames, particles lost to the domain), and a summary at the end.
// Warnings go to messages::warning, routine lines to the stage's progress (silenced by --quiet).
#include <cstddef>
#include <cstdint>

#include "sim/core/progress.h"
#include "sim/diffuse/simulator.h"
#include "sim/scene/sim_scene.h"

namespace spume {

class DiffuseRunNotes {
 public:
  // `frames`: how many frames this run simulates; `solids`: whether the run has any (a container, given
  // or inferred, holds the diffuse particles as it holds the water).
  DiffuseRunNotes(const SimScene& scene, Progress& progress, size_t frames, bool solids);

  // A frame's particles as handed over for writing (emission budget and caps).
  void written(const FrameStats& stats, int frame);
  // A frame simulated. `first`: the run's first frame; `next_frame`: the frame it was stepped to (-1 for
  // the last); `has_velocities`: whether the fluid frame stores velocities.
  void simulated(const FrameStats& stats, bool first, int next_frame, bool has_velocities);
  // The summary lines, after the last frame.
  void finish() const;

 private:
  void interior(const FrameStats& stats);
  void flip_density(const FrameStats& stats, bool first);

  const SimScene& scene_;
  Progress& progress_;
  size_t frames_;
  bool solids_;
  bool warned_budget_ = false, warned_cap_ = false, warned_band_skip_ = false, noted_pocket_ = false;
  bool warned_masses_ = false;
  int domain_warnings_ = 0;  // frames that lost more than 1% of what they emitted to the domain
  uint64_t landed_ = 0;      // diffuse particles deleted on the ground beside a tank
  int unpaired_frames_ = 0;  // frames without ids whose particles could not be paired with the next's
  int band_frames_ = 0;      // frames found to be a narrow band and filled (MODEL.md §9.1)
  size_t most_filled_ = 0;
  float least_density_ = 0.0f, most_density_ = 0.0f;  // fluid.particles = flip: the measured density ratios
};

}  // namespace spume
