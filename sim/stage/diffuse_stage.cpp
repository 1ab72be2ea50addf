#include "sim/stage/diffuse_stage.h"

#include <algorithm>
#include <optional>

#include "sim/stage/body_track_file.h"
#include "sim/stage/cache_state.h"
#include "sim/stage/diffuse_resume.h"
#include "sim/stage/diffuse_run_notes.h"
#include "sim/stage/diffuse_stats_csv.h"
#include "sim/io/file_identity.h"
#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/core/messages.h"
#include "sim/core/progress.h"
#include "sim/core/stopwatch.h"
#include "sim/diffuse/simulator.h"
#include "sim/io/background_writer.h"
#include "sim/io/bgeo.h"
#include "sim/io/cache_layout.h"
#include "sim/io/huge_buffer.h"
#include "sim/io/spume_cache.h"
#include "sim/scene/diffuse_params_reader.h"

namespace spume {
namespace {

// A sequence with a hole would be stepped across silently; the user decides (fluid.allow_gaps).
void check_no_gaps(const std::vector<int>& frames, const FluidSource& source) {
  const std::vector<int> missing = missing_frames(frames);
  if (missing.empty()) return;
  std::string list;
  for (size_t k = 0; k < std::min<size_t>(missing.size(), 8); ++k) list += str(k ? ", " : "", missing[k]);
  if (missing.size() > 8) list += str(" and ", missing.size() - 8, " more");
  fail(source.describe(), ": fluid frame ", missing.front(), " is missing (", missing.size() == 1 ? "frame " : "frames ",
       list, "); re-export it, limit fluid.frames to a range without gaps, or set fluid.allow_gaps to true "
       "(--allow-gaps) to interpolate missing frames between their neighbours");
}

}  // namespace

std::vector<int> diffuse_frames_to_run(const SimScene& scene, const FluidSource& source,
                                       const DiffuseStageOptions& options) {
  std::vector<int> available = source.frame_numbers();
  const auto range = options.frames ? options.frames : scene.frames;
  if (!range) {
    check_no_gaps(available, source);
    return available;
  }
  std::vector<int> chosen;
  for (int f : available)
    if (f >= range->first && f <= range->second) chosen.push_back(f);
  if (chosen.empty())
    fail("frames ", range->first, "-", range->second, ": none of them exist in ", source.describe());
  check_no_gaps(chosen, source);
  return chosen;
}

namespace {

Json box_json(const Aabb& b) {
  return Json::array({Json::array({b.min.x(), b.min.y(), b.min.z()}), Json::array({b.max.x(), b.max.y(), b.max.z()})});
}

// What the inputs resolved to beyond the keys (the default domain, an inferred tank): they depend on
// the whole sequence, so a change there is a change of what the caches would be.
Json resolved_json(const SimScene& scene, const SceneInputs& inputs) {
  Json tanks = Json::array();
  for (size_t k = scene.solids.solids().size(); k < inputs.solids.solids().size(); ++k)
    tanks.push_back(box_json(Aabb{inputs.solids.solids()[k].min, inputs.solids.solids()[k].max}));
  return {{"domain", box_json(inputs.domain)}, {"inferred_tanks", tanks}};
}

}  // namespace

StageRecord diffuse_stage_record(const SimScene& scene, const SceneInputs& inputs, const std::vector<int>& frames,
                                 const std::filesystem::path& scene_out) {
  StageRecord r;
  r.stage = "diffuse";
  r.keys = scene.diffuse_keys;
  r.keys["resolved"] = resolved_json(scene, inputs);
  r.first_frame = frames.front();
  r.last_frame = frames.back();
  for (const FrameSurvey& f : inputs.survey.frames)
    if (f.frame >= r.first_frame && f.frame <= r.last_frame) r.frame_inputs[f.frame] = f.file;
  if (scene.solids.any_dynamic()) r.other_inputs["bodies.csv"] = file_identity(body_track_path(scene_out));
  return r;
}

RecordMatch diffuse_caches_match(const SimScene& scene, const SceneInputs& inputs, const std::vector<int>& frames,
                                 const std::filesystem::path& scene_out, const std::vector<int>& needed_frames) {
  return cache_match(scene_out / "diffuse", diffuse_stage_record(scene, inputs, frames, scene_out),
                     [&](int f) { return diffuse_cache_path(scene_out, f); }, {}, needed_frames);
}

bool diffuse_caches_current(const SimScene& scene, const SceneInputs& inputs, const FluidSource& source,
                            const DiffuseStageOptions& options) {
  const std::vector<int> frames = diffuse_frames_to_run(scene, source, options);
  return diffuse_caches_match(scene, inputs, frames, options.out_root / scene.name).kind == RecordMatch::Kind::Current;
}

DiffuseStageSummary run_diffuse_stage(const SimScene& scene, const SceneInputs& inputs, FluidSource& source,
                                      const DiffuseStageOptions& options) {
  const Stopwatch start;
  const std::vector<int> frames = diffuse_frames_to_run(scene, source, options);
  DiffuseStageSummary summary;
  summary.out_dir = options.out_root / scene.name;
  const std::filesystem::path cache_dir = summary.out_dir / "diffuse";
  const StageRecord wanted = diffuse_stage_record(scene, inputs, frames, summary.out_dir);
  const RecordMatch match = diffuse_caches_match(scene, inputs, frames, summary.out_dir);
  if (!options.force && match.kind == RecordMatch::Kind::Current) {
    repeat_warnings(read_stage_record(cache_dir));
    summary.reused = true;
    summary.frames = int(frames.size());
    return summary;
  }
  DiffuseResume resume = find_diffuse_resume(match, frames, summary.out_dir, options.force);
  const size_t first = resume.index;
  if (first > 0) summary.continued_from = frames[first];
  summary.why = options.force ? "--force" : match.why;
  remove_stage_record(cache_dir);
  // The caches' buffers stay pooled from frame to frame, and go back to the system when the stage ends
  // (declared before the writer, so after its last file).
  struct ReleasePoolOnExit {
    ~ReleasePoolOnExit() { scratch_pool_release(); }
  } const release_pool;

  Progress progress("simulate " + scene.name, frames.size() - first, options.quiet);
  if (first > 0)
    progress.note(str("diffuse: continuing from frame ", frames[first], " (", match.why, ")"));
  else if (!resume.note.empty())
    progress.note(resume.note);
  else if (match.kind == RecordMatch::Kind::Stale && !options.force)
    progress.note(str("diffuse: simulating (", match.why, ")"));
  FluidFrame current = with_context(str("frame ", frames[first]), [&] { return source.load(frames[first]); });

  DiffuseSetup setup;
  setup.params = scene.diffuse;
  setup.fluid = scene.fluid;
  setup.solids = inputs.solids;
  setup.bodies = scene_body_track(scene, summary.out_dir);
  setup.domain = inputs.domain;
  setup.ground = inputs.solids.ground_below_tanks();
  setup.particles = scene.flip_particles ? FluidParticles::Flip : FluidParticles::Sph;
  setup.fill_narrow_band = scene.fill_narrow_band;
  DiffuseSimulator simulator(setup);
  if (first > 0) simulator.set_particles(std::move(*resume.state));

  write_file_atomically(summary.out_dir / "diffuse_params.json",
                        [&](std::ostream& out) { out << diffuse_params_to_json(scene.diffuse).dump(2) << '\n'; });
  DiffuseStatsCsv stats_csv(summary.out_dir / "stats.csv",
                            first > 0 ? std::optional<int>(frames[first]) : std::nullopt);
  DiffuseRunNotes notes(scene, progress, frames.size() - first, !inputs.solids.empty());
  BackgroundWriter writer;
  for (size_t k = first; k < frames.size(); ++k) {
    std::optional<FluidFrame> next;
    if (k + 1 < frames.size())
      next = with_context(str("frame ", frames[k + 1]), [&] { return source.load(frames[k + 1]); });
    const bool continued = k == first && first > 0;  // the frame continued from is on disk already
    double io_ms = 0.0;
    auto write_frame = [&](const DiffuseFrame& particles, const FrameStats& stats) {
      if (continued) return;
      // Encoded here, while the frame is ours; written on the writer's thread while the next frame is
      // simulated. io_ms: encoding, plus waiting for the previous frame's file.
      const Stopwatch t0;
      auto write_cache = [&](const std::filesystem::path& path, double position_step) {
        writer.write(path, encode_diffuse_cache(particles, position_step, path.string()));
      };
      write_cache(diffuse_cache_path(summary.out_dir, particles.index), scene.fluid.particle_radius / kPositionStepsPerRadius);
      if (k + 1 == frames.size()) {
        // The frame's cache is written before the restart is encoded, whose buffers then come from
        // the pool instead of adding to the peak (2.5 GB at 106M particles).
        writer.wait();
        write_cache(diffuse_restart_path(summary.out_dir, particles.index), 0.0);
        writer.wait();  // the last frame's files are on disk before its row is written
      }
      io_ms = t0.milliseconds();
      notes.written(stats, particles.index);
    };
    const FrameStats stats = with_context(str("frame ", frames[k]), [&] {
      return simulator.process_frame(current, next ? &*next : nullptr, write_frame);
    });
    notes.simulated(stats, k == first, next ? frames[k + 1] : -1, current.has_velocities());
    if (!continued) stats_csv.add(stats, current.time, io_ms);
    summary.max_diffuse = std::max(summary.max_diffuse, simulator.particles().size());
    summary.generated += stats.generated;
    ++summary.frames;
    progress.update(k + 1 - first, str(stats.by_type[0], " spray ", stats.by_type[1], " foam ", stats.by_type[2], " bubbles"));
    if (next) current = std::move(*next);
  }
  notes.finish();
  writer.wait();  // every frame's cache on disk before the stage is marked finished
  stats_csv.write();
  remove_diffuse_restarts(summary.out_dir, frames.back());
  StageRecord made = wanted;
  made.warnings = messages::warnings();
  if (first > 0 && resume.earlier) made.warnings = merged_warnings(resume.earlier->warnings, made.warnings);
  write_stage_record(cache_dir, made);
  summary.seconds = start.seconds();
  progress.finish(str("max ", summary.max_diffuse, " diffuse particles -> ", summary.out_dir.string()));
  return summary;
}

}  // namespace spume
