#include "render/app/output_folder_info.h"

#include <vector>

#include "sim/core/error.h"
#include "sim/io/stage_record.h"

namespace spume {

namespace fs = std::filesystem;

std::optional<OutputFolder> describe_output_folder(const fs::path& dir) {
  struct Stage {
    const char* folder;
    const char* what;
  };
  const std::vector<Stage> stages = {{"fluid", "fluid caches"},          {"fluid_bgeo", "fluid .bgeo export"},
                                     {"diffuse", "diffuse caches"},      {"diffuse_bgeo", "diffuse .bgeo export"},
                                     {"diffuse_vdb", "diffuse .vdb export"}, {"diffuse_fog", "fog volumes export"}};
  std::string text, details;
  size_t found = 0, warnings = 0;
  for (const Stage& s : stages) {
    const std::optional<StageRecord> record = read_stage_record(dir / s.folder);
    if (!record) continue;
    ++found;
    warnings += record->warnings.size();
    text += str("  ", s.what, " (", s.folder, "/): frames ", record->first_frame, "-", record->last_frame, ", ",
                record->warnings.size(), record->warnings.size() == 1 ? " warning" : " warnings",
                " when they were made\n");
    for (const std::string& w : record->warnings) details += str("    ", s.folder, ": ", w, "\n");
  }
  if (found == 0) return std::nullopt;
  OutputFolder folder;
  folder.description = str(dir.string(), ": a spume output folder\n", text, "  warnings: ", warnings, "\n", details);
  folder.warnings = warnings;
  return folder;
}

}  // namespace spume
