#pragma once
// spume info on a scene's output folder (OUT/<scene>): which stages have finished caches there, their
// frames, and the warnings given while they were made (kept in each stage's record, io/stage_record.h),
// so that a farm user finds them after the fact.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace spume {

struct OutputFolder {
  std::string description;  // lines for stdout
  size_t warnings = 0;      // kept in the records, in all
};

// The folder described, or nullopt when it holds no stage record (not an output folder).
std::optional<OutputFolder> describe_output_folder(const std::filesystem::path& dir);

}  // namespace spume
