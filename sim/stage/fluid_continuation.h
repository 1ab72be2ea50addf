#pragma once
// Continuing the fluid stage from the frames on disk instead of solving again from t = 0 (a later
// `--frames A-B` that reaches further than the last run). The continued frames are byte-identical to
// one uninterrupted run because the solver restarts from the exact state it had after the last
// cached frame (fluid/restart_state.h), which the stage saves as
//   OUT/<scene>/fluid/restart_0010.spr    the solver state after the last frame of the run (here 10)
// at the run's end and, with a record of the frames so far, during it (a killed run continues).
// Only the last frame's state is kept: it is all a later run needs, and a state per frame would
// double the folder's size. A scene with dynamic solids continues its body track (bodies.csv) too,
// from the poses the state carries. A folder whose restart file is missing, corrupt or does not agree
// with its last frame (and body track) is solved again from t = 0.
#include <filesystem>

#include "sim/io/cache_layout.h"  // fluid_restart_path
#include <optional>
#include <string>

#include "sim/fluid/restart_state.h"
#include "sim/geometry/body_track.h"
#include "sim/scene/sim_scene.h"

namespace spume {


// What the restart state is checked to be made from: the fluid keys (16 hex digits).
std::string fluid_restart_digest(const SimScene& scene);

struct FluidContinuation {
  int last_frame = -1;         // the last frame on disk: solving continues with the next one
  FluidRestartState state;     // the solver's state at that frame
  std::string stats;           // solver_stats.csv up to that frame (header and one row per frame)
  BodyTrack bodies;            // bodies.csv up to that frame (scenes with dynamic solids)
};

// The continuation of the current prefix in OUT/<scene>/fluid (the caller has matched its record
// as a prefix of the frames wanted), or nullopt with `why` saying why the stage must start again.
std::optional<FluidContinuation> find_fluid_continuation(const SimScene& scene,
                                                         const std::filesystem::path& scene_out, std::string& why);

// Removes restart files in the fluid folder other than frame `keep`'s (all when keep < 0).
void remove_fluid_restarts(const std::filesystem::path& scene_out, int keep = -1);

}  // namespace spume
