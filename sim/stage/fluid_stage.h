#pragma once
// The fluid stage of a solver scene: spume's DFSPH solver from t = 0 to the scene's last frame,
// one cache per frame at the scene's frame rate.
//   OUT/<scene>/fluid/fluid_0000.spf       positions, velocities, ids (io/spume_cache.h)
//   OUT/<scene>/fluid/solver_stats.csv     steps, time step, density error, iterations, fastest particle
//                                          per frame (kSolverStatsHeader)
//   OUT/<scene>/fluid/bodies.csv           the dynamic solids' poses per frame (body_track_file.h)
//   (output.fluid_bgeo: made from these caches afterwards, stage/stage_exports.h)
//   OUT/<scene>/fluid/restart_0000.spr     the solver's state after the last frame (fluid_continuation.h)
// Current caches (cache_state.h) are reused and the solver does not run; a folder holding more frames
// than asked for serves a shorter range; one holding a current prefix of the frames is continued
// from its last frame (the same bytes as one run), except with dynamic solids (fluid_continuation.h
// says why it then starts again). A stale or incomplete folder is simulated again from t = 0.
// A solver that blows up (fluid/blow_up.h) stops the stage with an error naming the frame; no
// record is written for the frames it did not finish.
#include <filesystem>
#include <optional>
#include <string>

#include "sim/io/cache_layout.h"
#include "sim/io/stage_record.h"

#include "sim/scene/sim_scene.h"

namespace spume {

// The columns of solver_stats.csv. max_speed is the fastest particle at the frame's time (m/s);
// seconds, the frame's wall clock, stays last.
inline constexpr const char* kSolverStatsHeader =
    "frame,time,steps,mean_dt,density_error_pct,max_density_error_pct,density_iterations,divergence_iterations,"
    "corrections,max_speed,step_cap_ms,retries,seconds";

struct FluidStageOptions {
  std::filesystem::path out_root = "out";
  bool quiet = false;
  bool force = false;  // simulate even when the caches are current
  std::optional<int> last_frame;  // solve only up to this frame (clamped to the scene's last)
  double partial_progress_interval = -1.0;  // s between progress lines within a frame (Progress's default: < 0)
};

struct FluidStageSummary {
  bool reused = false;  // the caches were current; the solver did not run
  int frames = 0;       // frames solved (all wanted frames when reused)
  int continued_from = -1;  // the cached frame the solver continued from (-1: solved from t = 0)
  size_t particles = 0;
  double seconds = 0.0;
  std::string why;  // when the solver ran: what made the caches stale
};


// What the stage makes for frames 0..last of the scene (io/stage_record.h).
StageRecord fluid_stage_record(const SimScene& scene, int last);
int fluid_stage_last_frame(const SimScene& scene, const FluidStageOptions& options);
// The fluid folder against frames 0..last of the scene.
RecordMatch fluid_caches_match(const SimScene& scene, const std::filesystem::path& out_root, int last);
// The solver's caches of a solver scene hold every frame of the scene, made from its current keys.
bool fluid_caches_current(const SimScene& scene, const std::filesystem::path& out_root);

// Requires scene.source == Solver.
FluidStageSummary run_fluid_stage(const SimScene& scene, const FluidStageOptions& options);

}  // namespace spume
