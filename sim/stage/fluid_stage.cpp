#include "sim/stage/fluid_stage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "sim/stage/body_track_file.h"
#include "sim/stage/cache_state.h"
#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/core/messages.h"
#include "sim/core/out_of_memory.h"
#include "sim/core/progress.h"
#include "sim/core/stopwatch.h"
#include "sim/fluid/solver.h"
#include "sim/stage/fluid_continuation.h"
#include "sim/io/bgeo.h"
#include "sim/io/frame_pattern.h"
#include "sim/io/cache_layout.h"
#include "sim/io/spume_cache.h"

namespace spume {
namespace {

// The fastest particle of a frame, m/s. A fluid meant to be calm that is not (the walls of a deep
// pool, README "Deep water") shows here long before the blow-up check stops a run.
double fastest_speed(const FluidFrame& frame) {
  float fastest = 0.0f;
  for (const Vec3f& v : frame.velocities) fastest = std::max(fastest, v.squaredNorm());
  return std::sqrt(double(fastest));
}

std::string stats_row(int frame, double time, const SolverStats& now, const SolverStats& before, double max_speed,
                      double seconds) {
  const uint64_t steps = now.steps - before.steps;
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "%d,%.6f,%llu,%.3e,%.5f,%.5f,%.2f,%.2f,%llu,%.4f,%.4f,%llu,%.3f\n", frame,
                time, static_cast<unsigned long long>(steps),
                steps ? (now.time - before.time) / double(steps) : 0.0, 100.0 * now.density_error,
                100.0 * now.max_density_error, now.average_density_iterations, now.average_divergence_iterations,
                static_cast<unsigned long long>(now.corrections), max_speed, 1e3 * now.step_cap,
                static_cast<unsigned long long>(now.retries), seconds);
  return buffer;
}

}  // namespace

StageRecord fluid_stage_record(const SimScene& scene, int last) {
  StageRecord r;
  r.stage = "fluid";
  r.keys = scene.fluid_keys;
  r.first_frame = 0;
  r.last_frame = last;
  return r;
}

int fluid_stage_last_frame(const SimScene& scene, const FluidStageOptions& options) {
  const int scene_last = scene.frames->second;
  return options.last_frame ? std::min(*options.last_frame, scene_last) : scene_last;
}

namespace {

std::vector<std::filesystem::path> body_files(const SimScene& scene, const std::filesystem::path& out) {
  if (scene.solids.any_dynamic()) return {body_track_path(out)};
  return {};
}

// Everything a later run continues from, for frames 0..last: the restart state, the body track,
// solver_stats.csv and the record. Written at the end of a run and, as checkpoints, during it.
void write_continuable_prefix(const SimScene& scene, const std::filesystem::path& out, const FluidSolver& solver,
                              int last, const BodyTrack& bodies, const std::string& stats) {
  if (scene.solids.any_dynamic()) write_body_track(body_track_path(out), bodies);
  FluidRestartState state = solver.restart_state(last);
  state.digest = fluid_restart_digest(scene);
  write_restart_state(fluid_restart_path(out, last), state);
  write_file_atomically(out / "fluid" / "solver_stats.csv", [&](std::ostream& o) { o << stats; });
  StageRecord made = fluid_stage_record(scene, last);
  made.warnings = messages::warnings();
  write_stage_record(out / "fluid", made);
  remove_fluid_restarts(out, last);
}

// A run saves where it is whenever the time since it last did is kCheckpointRatio times what that
// took (the first frame always): killed midway, the next run continues from the last save, and the
// saves cost at most 1/kCheckpointRatio of the run (the paper's tower: 100 MB every half minute).
constexpr double kCheckpointRatio = 50.0;

void remove_fluid_frames(const std::filesystem::path& out) {
  std::error_code ec;
  for (int f : find_pattern_frames(fluid_cache_pattern(out))) std::filesystem::remove(fluid_cache_path(out, f), ec);
}

}  // namespace

RecordMatch fluid_caches_match(const SimScene& scene, const std::filesystem::path& out_root, int last) {
  const std::filesystem::path out = out_root / scene.name;
  return cache_match(out / "fluid", fluid_stage_record(scene, last), [&](int f) { return fluid_cache_path(out, f); },
                     body_files(scene, out));
}

bool fluid_caches_current(const SimScene& scene, const std::filesystem::path& out_root) {
  return fluid_caches_match(scene, out_root, scene.frames->second).kind == RecordMatch::Kind::Current;
}

FluidStageSummary run_fluid_stage(const SimScene& scene, const FluidStageOptions& options) {
  if (scene.source != FluidSourceKind::Solver) fail(scene.name, ": the fluid stage needs fluid.source \"solver\"");
  const Stopwatch start;
  const std::filesystem::path out = options.out_root / scene.name;
  const std::filesystem::path dir = out / "fluid";
  const int last = fluid_stage_last_frame(scene, options);
  FluidStageSummary summary;

  const bool has_bodies = scene.solids.any_dynamic();
  const RecordMatch match = fluid_caches_match(scene, options.out_root, last);
  if (!options.force && match.kind == RecordMatch::Kind::Current) {
    repeat_warnings(read_stage_record(dir));
    summary.reused = true;
    summary.frames = last + 1;
    return summary;
  }
  summary.why = options.force ? "--force" : match.why;
  std::string restart_why;
  std::optional<FluidContinuation> resume;
  if (!options.force && match.kind == RecordMatch::Kind::Prefix)
    resume = find_fluid_continuation(scene, out, restart_why);

  // Built before anything on disk is touched: it refuses a scene that would not fit in memory.
  FluidSolver solver(scene.solver.params, scene.solver.blocks, scene.solids);
  if (resume) {
    try {
      solver.restore(resume->state);
    } catch (const Error& e) {  // restore checks before it changes anything: the solver is still at t = 0
      restart_why = e.what();
      resume.reset();
    }
  }
  // Continuing keeps the record: it still describes the frames it names, if this run is interrupted.
  if (!resume) {
    remove_stage_record(dir);
    remove_fluid_frames(out);
    remove_fluid_restarts(out);
  }
  const int first = resume ? resume->last_frame + 1 : 0;
  summary.continued_from = resume ? resume->last_frame : -1;
  summary.frames = last - first + 1;
  summary.particles = solver.size();

  Progress progress("fluid " + scene.name, size_t(summary.frames), options.quiet, options.partial_progress_interval);
  if (resume)
    progress.note(str("fluid: continuing from frame ", resume->last_frame, " (", summary.why, "; solver state ",
                         fluid_restart_path(out, resume->last_frame).string(), "): frames ", first, "-", last));
  else if (match.kind == RecordMatch::Kind::Prefix && !options.force)
    progress.note(str("fluid: re-solving from t = 0 (", match.why, "): cannot continue: ", restart_why));
  progress.note(str(solver.size(), " fluid particles, ", solver.stats().boundary_particles,
                       " boundary particles, frames ", first, "-", last, " at ", scene.fluid.fps, " fps, steps of at most ",
                       1e3 * solver.stats().step_cap, " ms (", summary.why, ")"));
  std::string stats = resume ? resume->stats : std::string(kSolverStatsHeader) + "\n";
  SolverStats before = solver.stats();
  double fastest = 0.0;  // of the frames made here, for the closing line
  int fastest_frame = first;
  BodyTrack bodies = resume ? resume->bodies : BodyTrack{};
  bodies.fps = scene.fluid.fps;
  Stopwatch since_checkpoint;
  double checkpoint_seconds = 0.0;  // what the last one took
  for (int f = first; f <= last; ++f) {
    const Stopwatch t0;
    const double t = double(f) / scene.fluid.fps;
    const size_t done = size_t(f - first);
    with_context(str("fluid frame ", f, " (t = ", solver.time(), " to ", t, " s)"), [&] {
      allocating("simulating the fluid", 0, [&] {
        solver.advance_to(t, [&] {
          if (progress.partial_due())
            progress.partial(done, str("frame ", f, ": ", solver.stats().steps - before.steps, " steps, t = ",
                                       solver.time(), " of ", t, " s"));
        });
      });
    });
    const FluidFrame frame = solver.frame(f);
    write_fluid_cache(fluid_cache_path(out, f), frame, scene.fluid.particle_radius);
    if (has_bodies) bodies.frames.push_back(solver.body_poses());
    const SolverStats now = solver.stats();
    // Said once per frame that needed it: what blew up, and the step the solver settled on.
    if (now.retries > before.retries)
      progress.note(str("fluid frame ", f, ": ", solver.last_retry_reason(), "; took the frame again from t = ",
                        before.time, " s with steps of at most ", 1e3 * now.step_cap, " ms (were ",
                        1e3 * before.step_cap, " ms)"));
    const double speed = fastest_speed(frame);
    if (speed > fastest) fastest = speed, fastest_frame = f;
    stats += stats_row(f, frame.time, now, before, speed, t0.seconds());
    progress.update(done + 1, str("frame ", f, ": ", now.steps - before.steps, " steps, density error ",
                                  100.0 * now.density_error, "%"));
    before = now;
    if (f < last && since_checkpoint.seconds() >= kCheckpointRatio * checkpoint_seconds) {
      const Stopwatch writing;
      write_continuable_prefix(scene, out, solver, f, bodies, stats);
      checkpoint_seconds = writing.seconds();
      since_checkpoint.restart();
    }
  }
  write_continuable_prefix(scene, out, solver, last, bodies, stats);
  summary.seconds = start.seconds();
  const SolverStats s = solver.stats();
  // The fastest particle is said, not judged: no threshold on it separates the runs that are right
  // from the ones that are not (README "Deep water"), but a reader who knows the flow can.
  progress.finish(str(s.steps, " steps, mean dt ", s.average_dt * 1e3, " ms, max density error ",
                      100.0 * s.max_density_error, "%, fastest particle ", fastest, " m/s (frame ",
                      fastest_frame, ") -> ", dir.string()));
  return summary;
}

}  // namespace spume
