#pragma once
// Which caches on disk are current. A cache folder holds per-frame files plus `record.json`
// (io/stage_record.h): the keys, frames and input files it was made from, written only once every
// frame is on disk. A stage reuses a folder whose record matches what it would make now and whose
// frame files all exist; it continues a folder that holds a current prefix of the frames when it
// can; otherwise it removes the record (so an interrupted run is never mistaken for a finished one)
// and makes the frames again.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "sim/io/stage_record.h"

namespace spume {

// The folder's record against `wanted`; a missing record reads as Stale ("unfinished or never
// made"), and a Current record with a frame file missing as Stale naming the file (`frame_path` gives
// each frame's file). The files asked for are those of `needed_frames`, or, when it is empty, every
// frame from wanted.first_frame up to the last both records share: a render needs only the frames it
// draws, so caches removed to save disk do not stop it from drawing the others.
RecordMatch cache_match(const std::filesystem::path& dir, const StageRecord& wanted,
                        const std::function<std::filesystem::path(int)>& frame_path,
                        const std::vector<std::filesystem::path>& other_files = {},
                        const std::vector<int>& needed_frames = {});

}  // namespace spume
