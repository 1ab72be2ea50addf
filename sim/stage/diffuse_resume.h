#pragma once
// Where the diffuse stage starts. A current prefix (an earlier, shorter range of the same sequence)
// is continued from its last frame: the diffuse state of a frame is the whole state the simulator
// carries to the next, so the continued frames equal one uninterrupted run's. That needs the exact
// state (the restart file the earlier run wrote, or an exact cache); without it the stage starts over.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/core/frames.h"
#include "sim/io/stage_record.h"

namespace spume {

struct DiffuseResume {
  size_t index = 0;                     // into the stage's frames; 0: from the start
  std::optional<DiffuseFrame> state;    // the exact state at frames[index], when index > 0
  std::optional<StageRecord> earlier;   // the record of the run continued from (its warnings)
  std::string note;                     // why a prefix was not continued, for the log
};

// `match`: how the caches on disk compare with the stage's record; `force`: start over regardless.
DiffuseResume find_diffuse_resume(const RecordMatch& match, const std::vector<int>& frames,
                                  const std::filesystem::path& scene_out, bool force);

// Removes the restart files other than `keep`'s (a frame number; -1 keeps none): earlier runs' last
// frames, which no later run continues from.
void remove_diffuse_restarts(const std::filesystem::path& scene_out, int keep);

}  // namespace spume
