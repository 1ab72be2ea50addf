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
// made"), and a Current record with a frame file missing as Stale naming the file (only the files
// up to wanted.last_frame are asked for: `frame_path` gives each frame's file).
RecordMatch cache_match(const std::filesystem::path& dir, const StageRecord& wanted,
                        const std::function<std::filesystem::path(int)>& frame_path,
                        const std::vector<std::filesystem::path>& other_files = {});

}  // namespace spume
