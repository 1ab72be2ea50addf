#include "simulate_run.h"

#include <chrono>
#include <cstdio>
#include <fstream>

#include "body_track_file.h"
#include "cache_state.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "diffuse/simulator.h"
#include "io/bgeo.h"
#include "io/spume_cache.h"
#include "scene/diffuse_params_reader.h"

namespace spume {
namespace {

std::string frame_name(const char* prefix, int frame, const char* extension) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%s_%04d%s", prefix, frame, extension);
  return buffer;
}

}  // namespace

std::vector<int> diffuse_frames_to_run(const SimScene& scene, const FluidSource& source,
                                       const SimulateOptions& options) {
  std::vector<int> available = source.frame_numbers();
  const auto range = options.frames ? options.frames : scene.frames;
  if (!range) return available;
  std::vector<int> chosen;
  for (int f : available)
    if (f >= range->first && f <= range->second) chosen.push_back(f);
  if (chosen.empty())
    fail("frames ", range->first, "-", range->second, ": none of them exist in ", source.describe());
  return chosen;
}

namespace {

void write_stats_header(std::ostream& out) {
  out << "frame,time,fluid,spray,foam,bubbles,generated,dissolved,removed,dropped";
  for (const char* stage : kStageNames) out << ',' << stage << "_ms";
  out << ",io_ms\n";
}

void write_stats_row(std::ostream& out, const FrameStats& s, double time, double io_ms) {
  out << s.frame << ',' << time << ',' << s.fluid << ',' << s.by_type[0] << ',' << s.by_type[1] << ','
      << s.by_type[2] << ',' << s.generated << ',' << s.dissolved << ',' << s.removed << ',' << s.dropped;
  char buffer[32];
  for (double ms : s.stage_ms) std::snprintf(buffer, sizeof buffer, ",%.2f", ms), out << buffer;
  std::snprintf(buffer, sizeof buffer, ",%.2f\n", io_ms);
  out << buffer;
}

}  // namespace

std::filesystem::path diffuse_cache_path(const std::filesystem::path& scene_out, int frame) {
  return scene_out / "diffuse" / frame_name("diffuse", frame, ".spd");
}

namespace {

// The diffuse material starts empty at the first frame, so the caches depend on it too.
std::string diffuse_fingerprint(const SimScene& scene, const std::vector<int>& frames) {
  return scene.diffuse_fingerprint + str("\nfirst frame ", frames[0]);
}

std::vector<std::filesystem::path> diffuse_cache_paths(const std::filesystem::path& scene_out,
                                                       const std::vector<int>& frames) {
  std::vector<std::filesystem::path> paths;
  for (int f : frames) paths.push_back(diffuse_cache_path(scene_out, f));
  return paths;
}

}  // namespace

bool diffuse_caches_current(const SimScene& scene, const FluidSource& source, const SimulateOptions& options) {
  const std::vector<int> frames = diffuse_frames_to_run(scene, source, options);
  const std::filesystem::path scene_out = options.out_root / scene.name;
  return cache_is_current(scene_out / "diffuse", diffuse_fingerprint(scene, frames),
                          diffuse_cache_paths(scene_out, frames));
}

SimulateSummary run_simulation(const SimScene& scene, const SceneInputs& inputs, FluidSource& source,
                               const SimulateOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<int> frames = diffuse_frames_to_run(scene, source, options);
  SimulateSummary summary;
  summary.out_dir = options.out_root / scene.name;
  const std::filesystem::path cache_dir = summary.out_dir / "diffuse";
  const std::string fingerprint = diffuse_fingerprint(scene, frames);
  const std::vector<std::filesystem::path> paths = diffuse_cache_paths(summary.out_dir, frames);
  if (!options.force && cache_is_current(cache_dir, fingerprint, paths)) {
    summary.reused = true;
    summary.frames = int(frames.size());
    return summary;
  }
  mark_cache_started(cache_dir);

  Progress progress("simulate " + scene.name, frames.size(), options.quiet);
  FluidFrame current = with_context(str("frame ", frames[0]), [&] { return source.load(frames[0]); });

  DiffuseSetup setup;
  setup.params = scene.diffuse;
  setup.fluid = scene.fluid;
  setup.solids = inputs.solids;
  setup.bodies = scene_body_track(scene, summary.out_dir);
  setup.domain = inputs.domain;
  DiffuseSimulator simulator(setup);

  write_file_atomically(summary.out_dir / "diffuse_params.json",
                        [&](std::ostream& out) { out << diffuse_params_to_json(scene.diffuse).dump(2) << '\n'; });
  std::string stats_text;
  {
    std::ostringstream header;
    write_stats_header(header);
    stats_text = header.str();
  }

  bool warned_budget = false;
  int domain_warnings = 0;  // frames that lost more than 1% of what they emitted to the domain
  for (size_t k = 0; k < frames.size(); ++k) {
    std::optional<FluidFrame> next;
    if (k + 1 < frames.size())
      next = with_context(str("frame ", frames[k + 1]), [&] { return source.load(frames[k + 1]); });
    double io_ms = 0.0;
    auto write_frame = [&](const DiffuseFrame& particles, const FrameStats& stats) {
      const auto t0 = std::chrono::steady_clock::now();
      write_diffuse_cache(diffuse_cache_path(summary.out_dir, particles.index), particles);
      if (scene.write_bgeo)
        write_bgeo(summary.out_dir / "diffuse_bgeo" / frame_name("diffuse", particles.index, ".bgeo"), particles);
      io_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (stats.dropped > 0 && !warned_budget) {
        progress.message(str("warning: the emission budget diffuse.max_particles = ", *scene.diffuse.max_particles,
                             " binds from frame ", particles.index,
                             ": emission is thinned uniformly at random (unbiased in space); see stats.csv 'dropped'"));
        warned_budget = true;
      }
    };
    const FrameStats stats = with_context(str("frame ", frames[k]), [&] {
      return simulator.process_frame(current, next ? &*next : nullptr, write_frame);
    });
    if (stats.generated > 0 && stats.removed * 100 > stats.generated) {
      if (++domain_warnings <= 3)
        progress.message(str("warning: frame ", stats.frame, " removed ", stats.removed, " diffuse particles outside the "
                             "domain, ", 100.0 * double(stats.removed) / double(stats.generated),
                             "% of the ", stats.generated, " emitted; if the flow reaches beyond the domain, widen "
                             "domain.min / domain.max"));
      if (domain_warnings == 3) progress.message("  (more frames like this are counted in stats.csv, column removed)");
    }
    std::ostringstream row;
    write_stats_row(row, stats, current.time, io_ms);
    stats_text += row.str();
    summary.max_diffuse = std::max(summary.max_diffuse, simulator.particles().size());
    summary.generated += stats.generated;
    ++summary.frames;
    progress.update(k + 1, str(stats.by_type[0], " spray ", stats.by_type[1], " foam ", stats.by_type[2], " bubbles"));
    if (next) current = std::move(*next);
  }
  write_file_atomically(summary.out_dir / "stats.csv", [&](std::ostream& out) { out << stats_text; });
  mark_cache_complete(cache_dir, fingerprint);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress.finish(str("max ", summary.max_diffuse, " diffuse particles -> ", summary.out_dir.string()));
  return summary;
}

}  // namespace spume
