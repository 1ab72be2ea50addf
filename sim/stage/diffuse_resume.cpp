#include "sim/stage/diffuse_resume.h"

#include <algorithm>
#include <system_error>

#include "sim/core/error.h"
#include "sim/io/cache_layout.h"
#include "sim/io/spume_cache.h"

namespace spume {
namespace {

// The exact diffuse state at `frame`: the restart file the run that made it wrote, or its cache when
// that is exact (version 1, raw); std::nullopt when neither exists (a quantized cache alone would
// continue from rounded positions, and the continued frames would differ from one uninterrupted run's).
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

}  // namespace

DiffuseResume find_diffuse_resume(const RecordMatch& match, const std::vector<int>& frames,
                                  const std::filesystem::path& scene_out, bool force) {
  DiffuseResume resume;
  if (force || match.kind != RecordMatch::Kind::Prefix) return resume;
  resume.earlier = read_stage_record(scene_out / "diffuse");
  const size_t last = size_t(std::find(frames.begin(), frames.end(), resume.earlier->last_frame) - frames.begin());
  if (last == 0 || last >= frames.size()) return resume;
  resume.state = exact_diffuse_state(scene_out, frames[last]);
  if (resume.state)
    resume.index = last;
  else
    resume.note = str("diffuse: simulating from the start (", diffuse_restart_path(scene_out, frames[last]).string(),
                      ", the exact state to continue from, is missing)");
  return resume;
}

void remove_diffuse_restarts(const std::filesystem::path& scene_out, int keep) {
  std::error_code ec;
  const std::string kept = keep >= 0 ? diffuse_restart_path(scene_out, keep).filename().string() : "";
  for (const auto& entry : std::filesystem::directory_iterator(scene_out / "diffuse", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("restart_", 0) == 0 && name.size() > 4 && name.substr(name.size() - 4) == ".spd" && name != kept)
      std::filesystem::remove(entry.path(), ec);
  }
}

}  // namespace spume
