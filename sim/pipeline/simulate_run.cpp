#include "sim/pipeline/simulate_run.h"

#include <cstdio>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <optional>

#include "sim/pipeline/body_track_file.h"
#include "sim/pipeline/cache_state.h"
#include "sim/io/file_identity.h"
#include "sim/core/huge_pages.h"
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

// The exact diffuse state at `frame` to continue from: the restart file the run that made it wrote,
// or its cache when that is exact (version 1, raw); std::nullopt when neither exists (a quantized
// cache alone would continue from rounded positions, and the continued frames would differ from one
// uninterrupted run's).
std::optional<DiffuseFrame> exact_diffuse_state(const std::filesystem::path& scene_out, int frame) {
  const std::filesystem::path restart = diffuse_restart_path(scene_out, frame);
  if (std::filesystem::is_regular_file(restart)) {
    DiffuseFrame state = read_diffuse_cache(restart);
    if (state.index == frame) return state;
  }
  const std::filesystem::path cache = diffuse_cache_path(scene_out, frame);
  if (!peek_diffuse_cache(cache).quantized) return read_diffuse_cache(cache);
  return std::nullopt;
}

// Restart files other than `keep`'s (a frame number; -1 keeps none): earlier runs' last frames.
void remove_diffuse_restarts(const std::filesystem::path& scene_out, int keep) {
  std::error_code ec;
  const std::string kept = keep >= 0 ? diffuse_restart_path(scene_out, keep).filename().string() : "";
  for (const auto& entry : std::filesystem::directory_iterator(scene_out / "diffuse", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("restart_", 0) == 0 && name.size() > 4 && name.substr(name.size() - 4) == ".spd" && name != kept)
      std::filesystem::remove(entry.path(), ec);
  }
}

}  // namespace

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
                                       const SimulateOptions& options) {
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

void write_stats_header(std::ostream& out) {
  out << "frame,time,fluid,spray,foam,bubbles,generated,dissolved,removed,dropped,capped";
  for (const char* stage : kStageNames) out << ',' << stage << "_ms";
  out << ",io_ms\n";
}

void write_stats_row(std::ostream& out, const FrameStats& s, double time, double io_ms) {
  out << s.frame << ',' << time << ',' << s.fluid << ',' << s.by_type[0] << ',' << s.by_type[1] << ','
      << s.by_type[2] << ',' << s.generated << ',' << s.dissolved << ',' << s.removed << ',' << s.dropped << ',' << s.capped;
  char buffer[32];
  for (double ms : s.stage_ms) std::snprintf(buffer, sizeof buffer, ",%.2f", ms), out << buffer;
  std::snprintf(buffer, sizeof buffer, ",%.2f\n", io_ms);
  out << buffer;
}

}  // namespace

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
                                 const std::filesystem::path& scene_out) {
  return cache_match(scene_out / "diffuse", diffuse_stage_record(scene, inputs, frames, scene_out),
                     [&](int f) { return diffuse_cache_path(scene_out, f); });
}

bool diffuse_caches_current(const SimScene& scene, const SceneInputs& inputs, const FluidSource& source,
                            const SimulateOptions& options) {
  const std::vector<int> frames = diffuse_frames_to_run(scene, source, options);
  return diffuse_caches_match(scene, inputs, frames, options.out_root / scene.name).kind == RecordMatch::Kind::Current;
}

namespace {

// The rows of an earlier stats.csv for frames up to `last`, header included ("" when unreadable).
std::string stats_rows_up_to(const std::filesystem::path& path, int last) {
  std::ifstream in(path);
  std::string line, kept;
  if (!std::getline(in, line)) return "";
  std::ostringstream header;
  write_stats_header(header);
  if (line + '\n' != header.str()) return "";  // columns of an older version: not mixed with today's rows
  kept = line + '\n';
  while (std::getline(in, line)) {
    const int frame = std::atoi(line.c_str());
    if (frame <= last) kept += line + '\n';
  }
  return kept;
}

}  // namespace

SimulateSummary run_simulation(const SimScene& scene, const SceneInputs& inputs, FluidSource& source,
                               const SimulateOptions& options) {
  const Stopwatch start;
  const std::vector<int> frames = diffuse_frames_to_run(scene, source, options);
  SimulateSummary summary;
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
  // A current prefix (an earlier, shorter range of the same sequence) is continued from its last
  // frame: the diffuse cache of a frame is the whole state the simulator carries to the next.
  size_t resume = 0;
  std::optional<StageRecord> earlier;  // the record of the prefix continued from, for its warnings
  if (!options.force && match.kind == RecordMatch::Kind::Prefix) {
    earlier = read_stage_record(cache_dir);
    const int made_last = earlier->last_frame;
    resume = size_t(std::find(frames.begin(), frames.end(), made_last) - frames.begin());
    if (resume >= frames.size()) resume = 0;
  }
  std::optional<DiffuseFrame> resume_state;
  std::string resume_note;
  if (resume > 0) {
    resume_state = exact_diffuse_state(summary.out_dir, frames[resume]);
    if (resume_state)
      summary.continued_from = frames[resume];
    else
      resume_note = str("diffuse: simulating from the start (", diffuse_restart_path(summary.out_dir, frames[resume]).string(),
                        ", the exact state to continue from, is missing)");
    if (!resume_state) resume = 0;
  }
  summary.why = options.force ? "--force" : match.why;
  remove_stage_record(cache_dir);
  const HugePagesForLargeBlocks huge_pages;  // the frame's arrays grow with it: fresh memory every frame
  // The caches' buffers stay pooled from frame to frame, and go back to the system when the stage ends
  // (declared before the writer, so after its last file).
  struct ReleasePoolOnExit {
    ~ReleasePoolOnExit() { scratch_pool_release(); }
  } const release_pool;

  Progress progress("simulate " + scene.name, frames.size() - resume, options.quiet);
  if (resume > 0)
    progress.note(str("diffuse: continuing from frame ", frames[resume], " (", match.why, ")"));
  else if (!resume_note.empty())
    progress.note(resume_note);
  else if (!options.quiet && match.kind == RecordMatch::Kind::Stale && !options.force)
    progress.note(str("diffuse: simulating (", match.why, ")"));
  FluidFrame current =
      with_context(str("frame ", frames[resume]), [&] { return source.load(frames[resume]); });

  DiffuseSetup setup;
  setup.params = scene.diffuse;
  setup.fluid = scene.fluid;
  setup.solids = inputs.solids;
  setup.bodies = scene_body_track(scene, summary.out_dir);
  setup.domain = inputs.domain;
  setup.particles = scene.flip_particles ? FluidParticles::Flip : FluidParticles::Sph;
  setup.fill_narrow_band = scene.fill_narrow_band;
  DiffuseSimulator simulator(setup);
  if (resume > 0) simulator.set_particles(std::move(*resume_state));

  write_file_atomically(summary.out_dir / "diffuse_params.json",
                        [&](std::ostream& out) { out << diffuse_params_to_json(scene.diffuse).dump(2) << '\n'; });
  std::string stats_text = resume > 0 ? stats_rows_up_to(summary.out_dir / "stats.csv", frames[resume]) : "";
  if (stats_text.empty()) {
    std::ostringstream header;
    write_stats_header(header);
    stats_text = header.str();
  }

  bool warned_budget = false, warned_cap = false;
  int domain_warnings = 0;  // frames that lost more than 1% of what they emitted to the domain
  int unpaired_frames = 0;  // frames without ids whose particles could not be paired with the next's
  int band_frames = 0;      // frames found to be a narrow band and filled (MODEL.md §9.1)
  size_t most_filled = 0;
  bool warned_band_skip = false, warned_pocket = false, warned_masses = false;
  float least_density = 0.0f, most_density = 0.0f;  // fluid.particles = flip: the measured density ratios
  BackgroundWriter writer;
  for (size_t k = resume; k < frames.size(); ++k) {
    std::optional<FluidFrame> next;
    if (k + 1 < frames.size())
      next = with_context(str("frame ", frames[k + 1]), [&] { return source.load(frames[k + 1]); });
    double io_ms = 0.0;
    auto write_frame = [&](const DiffuseFrame& particles, const FrameStats& stats) {
      if (k == resume && resume > 0) return;  // the frame continued from is on disk already
      // Encoded here, while the frame is ours; written on the writer's thread while the next frame is
      // simulated. io_ms: encoding, plus waiting for the previous frame's file.
      const Stopwatch t0;
      auto write_cache = [&](const std::filesystem::path& path, double position_step) {
        writer.write(path, encode_diffuse_cache(particles, position_step, path.string()));
      };
      write_cache(diffuse_cache_path(summary.out_dir, particles.index), scene.fluid.particle_radius / kPositionStepsPerRadius);
      if (k + 1 == frames.size()) {
        write_cache(diffuse_restart_path(summary.out_dir, particles.index), 0.0);
        writer.wait();  // the last frame's files are on disk before its row is written
      }
      if (scene.write_bgeo)
        write_bgeo(diffuse_bgeo_path(summary.out_dir, particles.index), particles);
      io_ms = t0.milliseconds();
      if (stats.dropped > 0 && !warned_budget) {
        messages::warning(str("the emission budget diffuse.max_particles = ", *scene.diffuse.max_particles,
                             " binds from frame ", particles.index,
                             ": emission is thinned uniformly at random (unbiased in space); see stats.csv 'dropped'"));
        warned_budget = true;
      }
      if (stats.capped > 0 && !warned_cap) {
        messages::warning(str("from frame ", particles.index, " Eq. 8 asks some fluid particles for more than ",
                             kMaxSamplesPerStep, " new diffuse particles in one step, the most a diffuse id can "
                             "number; ", stats.capped, " were not emitted in this frame (stats.csv 'capped' counts "
                             "every frame). More diffuse.substeps or lower diffuse.k_ta / diffuse.k_wc avoid it"));
        warned_cap = true;
      }
    };
    const FrameStats stats = with_context(str("frame ", frames[k]), [&] {
      return simulator.process_frame(current, next ? &*next : nullptr, write_frame);
    });
    if (stats.interior.narrow_band) {
      most_filled = std::max(most_filled, stats.interior.filled);
      if (++band_frames == 1)
        progress.note(str("frame ", stats.frame, "'s interior: ", describe_interior(stats.interior), "; filled with ",
                             stats.interior.filled, " massless particles for classification and advection "
                             "(MODEL.md §9.1; fluid.narrow_band = off leaves it empty)"));
    } else if (stats.interior.large && !warned_pocket) {
      progress.note(str("note: frame ", stats.frame, "'s interior: ", describe_interior(stats.interior), " (MODEL.md §9.1)"));
      warned_pocket = true;
    }
    if (stats.interior.skipped && !warned_band_skip) {
      progress.note(str("note: frame ", stats.frame, "'s particles spread over more than 16M cells of h; "
                           "such frames are not tested for an empty interior (MODEL.md §9.1)"));
      warned_band_skip = true;
    }
    if (scene.flip_particles) {
      if (k == resume)
        progress.note(str("fluid.particles = flip: velocities averaged over ", kVelocitySmoothing, " h for the "
                             "potentials; frame ", stats.frame, " holds ", stats.full_count, " particles in a full "
                             "neighbourhood (", stats.density_ratio, "x the nominal ",
                             4.0 / 3.0 * std::numbers::pi *
                                 std::pow(double(scene.fluid.support_radius) / (2.0 * scene.fluid.particle_radius), 3.0),
                             " at a spacing of 2r), counts and "
                             "rates taken at that density (MODEL.md §9.2)"));
      least_density = k == resume ? stats.density_ratio : std::min(least_density, stats.density_ratio);
      most_density = std::max(most_density, stats.density_ratio);
    }
    if (stats.unusable_masses.count > 0 && !warned_masses)
      messages::warning(str("frame ", stats.frame, ": ", stats.unusable_masses.describe(stats.fluid),
                           " (Houdini writes -1 where no mass was set): those particles take the uniform mass "
                           "rho0 (2r)^3 = ", scene.fluid.uniform_mass(), " kg for their kinetic energy"));
    warned_masses = warned_masses || stats.unusable_masses.count > 0;
    if (!stats.unpaired_because.empty() && ++unpaired_frames == 1)
      messages::warning(str("the fluid frames carry no particle ids, and from frame ", stats.frame, " to ",
                           frames[k + 1], " ", stats.unpaired_because, ": particles are not paired by index there; ",
                           current.has_velocities() ? "each moves with its stored velocity between frames"
                                                    : "without stored velocities they stand still between frames, "
                                                      "so foam and bubbles are not carried by the flow",
                           " (MODEL.md §8.16; a cache with an id attribute avoids it)"));
    if (stats.generated > 0 && stats.removed * 100 > stats.generated) {
      if (++domain_warnings <= 3)
        messages::warning(str("frame ", stats.frame, " removed ", stats.removed, " diffuse particles outside the "
                             "domain, ", 100.0 * double(stats.removed) / double(stats.generated),
                             "% of the ", stats.generated, " emitted; if the flow reaches beyond the domain, widen "
                             "domain.min / domain.max"));
      if (domain_warnings == 3)
        messages::warning("more frames may lose diffuse particles to the domain: stats.csv counts them, column removed");
    }
    if (!(k == resume && resume > 0)) {
      std::ostringstream row;
      write_stats_row(row, stats, current.time, io_ms);
      stats_text += row.str();
    }
    summary.max_diffuse = std::max(summary.max_diffuse, simulator.particles().size());
    summary.generated += stats.generated;
    ++summary.frames;
    progress.update(k + 1 - resume,
                    str(stats.by_type[0], " spray ", stats.by_type[1], " foam ", stats.by_type[2], " bubbles"));
    if (next) current = std::move(*next);
  }
  if (band_frames > 0)
    progress.note(str("  (", band_frames, " of ", frames.size() - resume, " frames were a narrow band, filled "
                         "with up to ", most_filled, " particles)"));
  if (scene.flip_particles)
    progress.note(str("  (fluid.particles = flip: particle density ", least_density, " to ", most_density,
                         "x the nominal over the frames)"));
  if (unpaired_frames > 1)
    messages::warning(str(unpaired_frames, " of ", frames.size() - 1 - resume,
                          " frame intervals left their particles unpaired (fluid frames without ids)"));
  writer.wait();  // every frame's cache on disk before the stage is marked finished
  write_file_atomically(summary.out_dir / "stats.csv", [&](std::ostream& out) { out << stats_text; });
  remove_diffuse_restarts(summary.out_dir, frames.back());
  StageRecord made = wanted;
  made.warnings = messages::warnings();
  if (resume > 0 && earlier) made.warnings = merged_warnings(earlier->warnings, made.warnings);
  write_stage_record(cache_dir, made);
  summary.seconds = start.seconds();
  progress.finish(str("max ", summary.max_diffuse, " diffuse particles -> ", summary.out_dir.string()));
  return summary;
}

}  // namespace spume
