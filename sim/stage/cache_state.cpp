#include "sim/stage/cache_state.h"

#include "sim/core/error.h"

namespace spume {

RecordMatch cache_match(const std::filesystem::path& dir, const StageRecord& wanted,
                        const std::function<std::filesystem::path(int)>& frame_path,
                        const std::vector<std::filesystem::path>& other_files,
                        const std::vector<int>& needed_frames) {
  const std::optional<StageRecord> made = read_stage_record(dir);
  if (!made) return {RecordMatch::Kind::Stale, "no finished caches: never made, or a run was interrupted"};
  RecordMatch match = match_records(*made, wanted);
  if (match.kind == RecordMatch::Kind::Stale) return match;
  const int last = std::min(made->last_frame, wanted.last_frame);
  auto missing = [&](int f) { return !std::filesystem::is_regular_file(frame_path(f)); };
  for (int f : needed_frames)
    if (f <= last && missing(f)) return {RecordMatch::Kind::Stale, str(frame_path(f).string(), " is missing")};
  for (int f = wanted.first_frame; needed_frames.empty() && f <= last; ++f)
    if (missing(f)) return {RecordMatch::Kind::Stale, str(frame_path(f).string(), " is missing")};
  for (const auto& file : other_files)
    if (!std::filesystem::is_regular_file(file)) return {RecordMatch::Kind::Stale, str(file.string(), " is missing")};
  return match;
}

}  // namespace spume
