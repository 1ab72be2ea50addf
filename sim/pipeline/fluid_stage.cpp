#include "fluid_stage.h"

#include <chrono>
#include <cstdio>
#include <sstream>

#include "body_track_file.h"
#include "cache_state.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "fluid/solver.h"
#include "io/bgeo.h"
#include "io/spume_cache.h"

namespace spume {
namespace {

std::string numbered(const char* prefix, int frame, const char* extension) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%s_%04d%s", prefix, frame, extension);
  return buffer;
}

std::string stats_row(int frame, double time, const SolverStats& now, const SolverStats& before, double seconds) {
  const uint64_t steps = now.steps - before.steps;
  char buffer[256];
  std::snprintf(buffer, sizeof buffer, "%d,%.6f,%llu,%.3e,%.5f,%.5f,%.2f,%.2f,%llu,%.3f\n", frame, time,
                static_cast<unsigned long long>(steps), steps ? (now.time - before.time) / double(steps) : 0.0,
                100.0 * now.density_error, 100.0 * now.max_density_error, now.average_density_iterations,
                now.average_divergence_iterations, static_cast<unsigned long long>(now.corrections), seconds);
  return buffer;
}

}  // namespace

std::filesystem::path fluid_cache_path(const std::filesystem::path& scene_out, int frame) {
  return scene_out / "fluid" / numbered("fluid", frame, ".spf");
}

std::string fluid_cache_pattern(const std::filesystem::path& scene_out) {
  return (scene_out / "fluid" / "fluid_%04d.spf").string();
}

namespace {

// Every file the stage writes per frame, and the body track of a scene with dynamic solids.
std::vector<std::filesystem::path> fluid_cache_paths(const SimScene& scene, const std::filesystem::path& scene_out) {
  std::vector<std::filesystem::path> paths;
  for (int f = 0; f <= scene.frames->second; ++f) paths.push_back(fluid_cache_path(scene_out, f));
  if (scene.solids.any_dynamic()) paths.push_back(body_track_path(scene_out));
  return paths;
}

}  // namespace

bool fluid_caches_current(const SimScene& scene, const std::filesystem::path& out_root) {
  const std::filesystem::path out = out_root / scene.name;
  return cache_is_current(out / "fluid", scene.fluid_fingerprint, fluid_cache_paths(scene, out));
}

FluidStageSummary run_fluid_stage(const SimScene& scene, const FluidStageOptions& options) {
  if (scene.source != FluidSourceKind::Solver) fail(scene.name, ": the fluid stage needs fluid.source \"solver\"");
  const auto start = std::chrono::steady_clock::now();
  const std::filesystem::path out = options.out_root / scene.name;
  const std::filesystem::path dir = out / "fluid";
  const int last = scene.frames->second;
  FluidStageSummary summary;
  summary.frames = last + 1;

  const std::vector<std::filesystem::path> paths = fluid_cache_paths(scene, out);
  const bool has_bodies = scene.solids.any_dynamic();
  if (!options.force && cache_is_current(dir, scene.fluid_fingerprint, paths)) {
    summary.reused = true;
    return summary;
  }
  mark_cache_started(dir);

  FluidSolver solver(scene.solver.params, scene.solver.blocks, scene.solids);
  summary.particles = solver.size();
  Progress progress("fluid " + scene.name, size_t(last) + 1, options.quiet);
  progress.message(str(solver.size(), " fluid particles, ", solver.stats().boundary_particles,
                       " boundary particles, frames 0-", last, " at ", scene.fluid.fps, " fps"));
  std::string stats =
      "frame,time,steps,mean_dt,density_error_pct,max_density_error_pct,density_iterations,divergence_iterations,"
      "corrections,seconds\n";
  SolverStats before = solver.stats();
  BodyTrack bodies;
  bodies.fps = scene.fluid.fps;
  for (int f = 0; f <= last; ++f) {
    const auto t0 = std::chrono::steady_clock::now();
    solver.advance_to(double(f) / scene.fluid.fps);
    const FluidFrame frame = solver.frame(f);
    write_fluid_cache(paths[size_t(f)], frame, scene.fluid.particle_radius);
    if (has_bodies) bodies.frames.push_back(solver.body_poses());
    if (scene.write_fluid_bgeo) write_bgeo(out / "fluid_bgeo" / numbered("fluid", f, ".bgeo"), frame);
    const SolverStats now = solver.stats();
    stats += stats_row(f, frame.time, now, before,
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    progress.update(size_t(f) + 1, str(now.steps - before.steps, " steps, density error ",
                                       100.0 * now.density_error, "%"));
    before = now;
  }
  if (has_bodies) write_body_track(body_track_path(out), bodies);
  write_file_atomically(dir / "solver_stats.csv", [&](std::ostream& o) { o << stats; });
  mark_cache_complete(dir, scene.fluid_fingerprint);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const SolverStats s = solver.stats();
  progress.finish(str(s.steps, " steps, mean dt ", s.average_dt * 1e3, " ms, max density error ",
                      100.0 * s.max_density_error, "% -> ", dir.string()));
  return summary;
}

}  // namespace spume
