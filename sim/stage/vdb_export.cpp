#include "sim/stage/vdb_export.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/core/progress.h"
#include "sim/core/stopwatch.h"
#include "sim/io/cache_layout.h"
#include "sim/io/file_identity.h"
#include "sim/io/spume_cache.h"
#include "sim/io/stage_record.h"
#include "sim/io/vdb_points_writer.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

fs::path vdb_dir(const fs::path& scene_out) { return diffuse_vdb_path(scene_out, 0).parent_path(); }

// The per-frame .vdb files in the folder (diffuse_<digits>.vdb), by frame number.
std::map<int, fs::path> vdb_files_on_disk(const fs::path& dir) {
  std::map<int, fs::path> found;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return found;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    constexpr std::string_view prefix = "diffuse_", suffix = ".vdb";
    if (name.size() <= prefix.size() + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix)) continue;
    const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.empty() || digits.size() > 9 || !std::all_of(digits.begin(), digits.end(), ::isdigit)) continue;
    found[std::stoi(digits)] = entry.path();
  }
  return found;
}

StageRecord wanted_record(const SimScene& scene, const std::vector<int>& frames, const fs::path& scene_out) {
  StageRecord r;
  r.stage = "diffuse_vdb";
  r.keys = {{"format", vdb_points_format(vdb_points_voxel_size(scene.fluid.particle_radius))}};
  r.first_frame = frames.empty() ? 0 : frames.front();
  r.last_frame = frames.empty() ? -1 : frames.back();
  for (int f : frames) r.frame_inputs[f] = file_identity(diffuse_cache_path(scene_out, f));
  return r;
}

// What bringing the folder in line takes.
struct Plan {
  std::vector<int> write;           // frames whose .vdb is missing or made from other caches or format
  std::vector<fs::path> remove;     // .vdb files of frames outside the range (all of them when off)
  std::optional<StageRecord> wanted;  // output.vdb on: the record to leave
  bool record_differs = false;      // the record on disk is not `wanted` (or is there while off)
  std::string why;                  // the first reason anything changes
};

Plan plan_export(const SimScene& scene, const std::vector<int>& frames, const fs::path& scene_out) {
  Plan plan;
  const fs::path dir = vdb_dir(scene_out);
  const std::map<int, fs::path> on_disk = vdb_files_on_disk(dir);
  const std::optional<StageRecord> made = read_stage_record(dir);
  if (!scene.write_vdb) {
    for (const auto& [frame, path] : on_disk) plan.remove.push_back(path);
    plan.record_differs = made.has_value();
    if (!on_disk.empty()) plan.why = "output.vdb is off";
    return plan;
  }
  plan.wanted = wanted_record(scene, frames, scene_out);
  const StageRecord& wanted = *plan.wanted;
  const std::set<int> range(frames.begin(), frames.end());
  for (int f : frames) {
    std::string why;
    if (!made)
      why = "no finished .vdb files: output.vdb newly on, or an export was interrupted";
    else if (made->keys != wanted.keys)
      why = json_difference(made->keys, wanted.keys);
    else if (!on_disk.count(f))
      why = str(diffuse_vdb_path(scene_out, f).string(), " is missing");
    else if (!made->frame_inputs.count(f) || made->frame_inputs.at(f) != wanted.frame_inputs.at(f))
      why = str("the diffuse cache of frame ", f, " changed");
    if (why.empty()) continue;
    plan.write.push_back(f);
    if (plan.why.empty()) plan.why = why;
  }
  // Frames outside the range (a shorter run after a longer one) stay while the .spd they were made
  // from is unchanged, and stay in the record; any other .vdb there goes.
  for (const auto& [frame, path] : on_disk) {
    if (range.count(frame)) continue;
    const fs::path spd = diffuse_cache_path(scene_out, frame);
    std::error_code ec;
    if (made && made->keys == wanted.keys && made->frame_inputs.count(frame) && fs::is_regular_file(spd, ec) &&
        file_identity(spd) == made->frame_inputs.at(frame)) {
      plan.wanted->frame_inputs[frame] = made->frame_inputs.at(frame);
      continue;
    }
    plan.remove.push_back(path);
    if (plan.why.empty()) plan.why = str(path.string(), " was made from another diffuse cache");
  }
  if (!plan.wanted->frame_inputs.empty()) {
    plan.wanted->first_frame = plan.wanted->frame_inputs.begin()->first;
    plan.wanted->last_frame = plan.wanted->frame_inputs.rbegin()->first;
  }
  plan.record_differs = !made || made->to_json() != plan.wanted->to_json();
  return plan;
}

}  // namespace

bool diffuse_vdb_current(const SimScene& scene, const std::vector<int>& frames, const fs::path& scene_out) {
  const Plan plan = plan_export(scene, frames, scene_out);
  return plan.write.empty() && plan.remove.empty() && !plan.record_differs;
}

VdbExportSummary export_diffuse_vdb(const SimScene& scene, const std::vector<int>& frames, const fs::path& scene_out,
                                    bool quiet) {
  const Stopwatch start;
  VdbExportSummary summary;
  const fs::path dir = vdb_dir(scene_out);
  const Plan plan = plan_export(scene, frames, scene_out);
  summary.why = plan.why;
  summary.kept = scene.write_vdb ? int(frames.size() - plan.write.size()) : 0;
  if (plan.write.empty() && plan.remove.empty() && !plan.record_differs) return summary;

  // The record goes first, so an interrupted export is never taken for a finished one.
  remove_stage_record(dir);
  remove_dead_temporaries(dir);
  const float voxel = vdb_points_voxel_size(scene.fluid.particle_radius);
  Progress progress("vdb " + scene.name, plan.write.size(), quiet);
  if (!plan.write.empty())
    progress.note(str("diffuse_vdb: writing ", plan.write.size(), " of ", frames.size(), " frames (", plan.why, ")"));
  for (size_t k = 0; k < plan.write.size(); ++k) {
    const int f = plan.write[k];
    const DiffuseFrame frame = read_diffuse_cache(diffuse_cache_path(scene_out, f));
    write_vdb_points(diffuse_vdb_path(scene_out, f), frame, voxel);
    ++summary.written;
    progress.update(k + 1, str(frame.size(), " points"));
  }
  for (const fs::path& path : plan.remove) {
    std::error_code ec;
    if (!fs::remove(path, ec) && ec) fail(path.string(), ": cannot remove a stale .vdb file: ", ec.message());
    ++summary.removed;
  }
  if (summary.removed > 0)
    progress.note(str("diffuse_vdb: removed ", summary.removed, " .vdb files (", plan.why, ")"));
  if (plan.wanted) write_stage_record(dir, *plan.wanted);
  std::error_code ec;
  if (!scene.write_vdb) fs::remove(dir, ec);  // only when empty: anything else in it is not spume's
  summary.seconds = start.seconds();
  if (summary.written > 0) progress.finish(str("-> ", dir.string()));
  return summary;
}

}  // namespace spume
