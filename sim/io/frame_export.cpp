#include "sim/io/frame_export.h"

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
#include "sim/io/stage_record.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

fs::path export_dir(const FrameExport& e, const fs::path& scene_out) { return scene_out / e.folder; }

// The export's per-frame files in its folder (<prefix>_<digits><extension>), by frame number.
std::map<int, fs::path> files_on_disk(const FrameExport& e, const fs::path& dir) {
  std::map<int, fs::path> found;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return found;
  const std::string prefix = e.prefix + "_";
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() + e.extension.size() || !name.starts_with(prefix) || !name.ends_with(e.extension))
      continue;
    const std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - e.extension.size());
    if (digits.empty() || digits.size() > 9 || !std::all_of(digits.begin(), digits.end(), ::isdigit)) continue;
    found[std::stoi(digits)] = entry.path();
  }
  return found;
}

// "3, 5-7, 11-20": sorted frame numbers as runs.
std::string frame_runs(const std::vector<int>& frames) {
  std::string text;
  for (size_t i = 0; i < frames.size();) {
    size_t j = i;
    while (j + 1 < frames.size() && frames[j + 1] == frames[j] + 1) ++j;
    text += str(text.empty() ? "" : ", ", frames[i]);
    if (j > i) text += str("-", frames[j]);
    i = j + 1;
  }
  return text;
}

StageRecord wanted_record(const FrameExport& e, const std::vector<int>& frames) {
  StageRecord r;
  r.stage = e.folder;
  r.keys = e.format;
  r.first_frame = frames.empty() ? 0 : frames.front();
  r.last_frame = frames.empty() ? -1 : frames.back();
  for (int f : frames) r.frame_inputs[f] = file_identity(e.cache_of(f));
  return r;
}

// What bringing the folder in line takes.
struct Plan {
  std::vector<int> write;             // frames whose file is missing or made from another cache or format
  std::vector<int> remove;            // files of frames that are not the stage's (all of them when off)
  std::map<int, fs::path> on_disk;
  std::optional<StageRecord> wanted;  // the export on: the record to leave
  bool record_differs = false;        // the record on disk is not `wanted` (or is there while off)
  std::string why_write, why_remove;  // the first reason for each
};

Plan plan_export(const FrameExport& e, const std::vector<int>& frames, const fs::path& scene_out) {
  Plan plan;
  const fs::path dir = export_dir(e, scene_out);
  plan.on_disk = files_on_disk(e, dir);
  const std::optional<StageRecord> made = read_stage_record(dir);
  if (!e.on) {
    for (const auto& [frame, path] : plan.on_disk) plan.remove.push_back(frame);
    plan.record_differs = made.has_value();
    plan.why_remove = str(e.key, " is off");
    return plan;
  }
  plan.wanted = wanted_record(e, frames);
  const StageRecord& wanted = *plan.wanted;
  for (int f : frames) {
    std::string why;
    if (!made)
      why = str("no finished ", e.extension, " files: ", e.key, " newly on, or an export was interrupted");
    else if (made->keys != wanted.keys)
      why = json_difference(made->keys, wanted.keys);
    else if (!plan.on_disk.count(f))
      why = str(export_file_path(e, scene_out, f).string(), " is missing");
    else if (!made->frame_inputs.count(f) || made->frame_inputs.at(f) != wanted.frame_inputs.at(f))
      why = str("the cache of frame ", f, " changed");
    if (why.empty()) continue;
    plan.write.push_back(f);
    if (plan.why_write.empty()) plan.why_write = why;
  }
  const std::set<int> range(frames.begin(), frames.end());
  for (const auto& [frame, path] : plan.on_disk)
    if (!range.count(frame)) plan.remove.push_back(frame);
  if (!plan.remove.empty())
    plan.why_remove = str("frames of an earlier run: this run's caches are frames ", frame_runs(frames));
  plan.record_differs = !made || made->to_json() != wanted.to_json();
  return plan;
}

}  // namespace

fs::path export_file_path(const FrameExport& e, const fs::path& scene_out, int frame) {
  return export_dir(e, scene_out) / numbered_file_name(e.prefix, frame, e.extension);
}

bool export_current(const FrameExport& e, const std::vector<int>& frames, const fs::path& scene_out) {
  const Plan plan = plan_export(e, frames, scene_out);
  return plan.write.empty() && plan.remove.empty() && !plan.record_differs;
}

FrameExportSummary bring_export_in_line(const FrameExport& e, const std::vector<int>& frames,
                                        const fs::path& scene_out, bool quiet) {
  const Stopwatch start;
  FrameExportSummary summary;
  const fs::path dir = export_dir(e, scene_out);
  const Plan plan = plan_export(e, frames, scene_out);
  summary.why = !plan.why_write.empty() ? plan.why_write : plan.why_remove;
  summary.kept = e.on ? int(frames.size() - plan.write.size()) : 0;
  if (plan.write.empty() && plan.remove.empty() && !plan.record_differs) return summary;

  remove_stage_record(dir);
  remove_dead_temporaries(dir);
  Progress progress(e.folder + " " + scene_out.filename().string(), plan.write.size(), quiet);
  // Stale files go before new ones are made: an interrupted run never leaves two runs' files together.
  for (int frame : plan.remove) {
    std::error_code ec;
    const fs::path& path = plan.on_disk.at(frame);
    if (!fs::remove(path, ec) && ec) fail(path.string(), ": cannot remove a stale ", e.extension, " file: ", ec.message());
    ++summary.removed;
  }
  if (summary.removed > 0)
    progress.note(str(e.folder, ": removed ", summary.removed, " ", e.extension, " files of frames ",
                      frame_runs(plan.remove), " (", plan.why_remove, ")"));
  if (!plan.write.empty())
    progress.note(str(e.folder, ": writing ", plan.write.size(), " of ", frames.size(), " frames (", plan.why_write, ")"));
  for (size_t k = 0; k < plan.write.size(); ++k) {
    e.write(plan.write[k], export_file_path(e, scene_out, plan.write[k]));
    ++summary.written;
    progress.update(k + 1, str("frame ", plan.write[k]));
  }
  if (plan.wanted) write_stage_record(dir, *plan.wanted);
  std::error_code ec;
  if (!e.on) fs::remove(dir, ec);  // only when empty: anything else in it is not spume's
  summary.seconds = start.seconds();
  if (summary.written > 0) progress.finish(str("-> ", dir.string()));
  return summary;
}

}  // namespace spume
