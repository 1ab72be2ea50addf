#include "sim/stage/fluid_continuation.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "sim/core/error.h"
#include "sim/io/cache_layout.h"
#include "sim/io/frame_pattern.h"
#include "sim/io/spume_cache.h"
#include "sim/io/stage_record.h"
#include "sim/stage/body_track_file.h"
#include "sim/stage/fluid_stage.h"

namespace spume {
namespace {

// The header and the rows of frames 0..last of solver_stats.csv, or "" when they are not all there
// or have other columns than this build writes (a file from an older spume).
std::string stats_rows(const std::filesystem::path& path, int last) {
  std::ifstream in(path);
  std::string line, kept;
  if (!std::getline(in, line) || line != kSolverStatsHeader) return "";
  kept = line + "\n";
  for (int f = 0; f <= last; ++f) {
    if (!std::getline(in, line) || line.rfind(std::to_string(f) + ",", 0) != 0) return "";
    kept += line + "\n";
  }
  return kept;
}

// The state must be the one the last cached frame was written from (frames hold particle id at index id).
bool agrees_with_frame(const FluidRestartState& s, const FluidFrame& frame) {
  const size_t n = s.size();
  if (frame.size() != n || frame.ids.size() != n || frame.velocities.size() != n || frame.time != s.time) return false;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t id = s.ids[k];
    if (id >= n || frame.ids[id] != id || frame.positions[id] != s.positions[k] ||
        frame.velocities[id] != s.velocities[k])
      return false;
  }
  return true;
}

// Frames 0..state.frame of the body track at `path`, whose last must hold the state's poses exactly.
BodyTrack body_track_prefix(const FluidRestartState& s, const std::filesystem::path& path, double fps) {
  BodyTrack track = read_body_track(path, fps);
  const size_t frames = size_t(s.frame) + 1;
  if (track.first_frame != 0 || track.frames.size() < frames)
    fail(path.string(), " holds frames ", track.first_frame, "-", track.first_frame + int(track.frames.size()) - 1,
         "; frames 0-", s.frame, " wanted");
  track.frames.resize(frames);
  const std::vector<BodyPose>& last = track.frames.back();
  auto same = [](const BodyPose& a, const BodyPose& b) {
    return a.solid == b.solid && a.position == b.position && a.orientation.coeffs() == b.orientation.coeffs() &&
           a.velocity == b.velocity && a.angular_velocity == b.angular_velocity;
  };
  if (last.size() != s.bodies.size() || !std::equal(last.begin(), last.end(), s.bodies.begin(), same))
    fail(path.string(), ": the poses of frame ", s.frame, " are not the restart state's");
  return track;
}

}  // namespace

std::string fluid_restart_digest(const SimScene& scene) { return record_digest(scene.fluid_keys); }

std::optional<FluidContinuation> find_fluid_continuation(const SimScene& scene,
                                                         const std::filesystem::path& scene_out, std::string& why) {
  const std::optional<StageRecord> record = read_stage_record(scene_out / "fluid");
  if (!record) {
    why = "the fluid folder has no record";
    return std::nullopt;
  }
  FluidContinuation c;
  c.last_frame = record->last_frame;
  const std::filesystem::path path = fluid_restart_path(scene_out, c.last_frame);
  if (!std::filesystem::is_regular_file(path)) {
    why = str(path.string(), " is missing (caches of an older spume, or removed), so the solver state at frame ",
              c.last_frame, " is unknown");
    return std::nullopt;
  }
  try {
    c.state = read_restart_state(path);
    if (c.state.frame != c.last_frame || c.state.digest != fluid_restart_digest(scene) ||
        c.state.time != double(c.last_frame) / scene.fluid.fps)
      fail(path.string(), ": made for frame ", c.state.frame, " at t = ", c.state.time, " s with keys ",
           c.state.digest, "; wanted frame ", c.last_frame, " with keys ", fluid_restart_digest(scene));
    if (!agrees_with_frame(c.state, read_fluid_cache(fluid_cache_path(scene_out, c.last_frame))))
      fail(path.string(), " does not hold the particles of ", fluid_cache_path(scene_out, c.last_frame).string());
    if (scene.solids.any_dynamic()) c.bodies = body_track_prefix(c.state, body_track_path(scene_out), scene.fluid.fps);
  } catch (const Error& e) {
    why = e.what();
    return std::nullopt;
  }
  c.stats = stats_rows(scene_out / "fluid" / "solver_stats.csv", c.last_frame);
  if (c.stats.empty()) {
    why = str("fluid/solver_stats.csv does not hold the rows of frames 0-", c.last_frame, " with the columns ",
              kSolverStatsHeader);
    return std::nullopt;
  }
  return c;
}

void remove_fluid_restarts(const std::filesystem::path& scene_out, int keep) {
  std::error_code ec;
  for (int f : find_pattern_frames(fluid_restart_pattern(scene_out)))
    if (f != keep) std::filesystem::remove(fluid_restart_path(scene_out, f), ec);
}

}  // namespace spume
