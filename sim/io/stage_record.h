#pragma once
// What a stage's outputs were made from, so that a rerun can tell current outputs from stale ones
// and say why. A cache folder holds `record.json` once every frame in it is on disk (a folder
// without one is unfinished); a rendered frame carries its record in the PNG (render/image/png_io.h).
//
// A record holds the scene keys the stage depends on (canonical JSON), the frames it made, and the
// identity (io/file_identity.h: size and modification time) of every input file it read, per frame.
// Outputs are current when the keys are equal, the first frame is the same, the wanted frames were
// made, and every input they were made from is unchanged. A later run that wants more frames of the
// same sequence can continue a current prefix instead of starting again.
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/io/file_identity.h"

namespace spume {

struct StageRecord {
  std::string stage;                         // "fluid", "diffuse"
  nlohmann::json keys = nlohmann::json::object();
  int first_frame = 0, last_frame = -1;      // inclusive range made (last < first: none yet)
  std::map<int, FileIdentity> frame_inputs;  // the input file each made frame was computed from
  std::map<std::string, FileIdentity> other_inputs;  // files read for the whole sequence, by name
  // The warnings given while these outputs were made (core/messages.h), said again whenever they are
  // reused; not part of what makes outputs current.
  std::vector<std::string> warnings;

  nlohmann::json to_json() const;
  static StageRecord from_json(const nlohmann::json& j);  // throws Error on a malformed record
};

// How `made` (on disk) relates to `wanted` (what this run would make).
struct RecordMatch {
  enum class Kind { Current, Prefix, Stale } kind = Kind::Stale;
  std::string why;  // Stale: the first difference, e.g. "diffuse.drag was 0.5, now 0.9"
};
RecordMatch match_records(const StageRecord& made, const StageRecord& wanted);

// The first path at which two JSON values differ, with both values ("" when equal), e.g.
// "diffuse.drag: 0.5 -> 0.9" or "render.spray: absent -> {...}".
std::string json_difference(const nlohmann::json& before, const nlohmann::json& now, const std::string& path = "");

// A short stable digest (16 hex digits, FNV-1a 64) of a record's canonical text.
std::string record_digest(const nlohmann::json& j);

// The folder's record: nullopt when there is none (never finished, or a stage started since).
// A corrupt record is treated as none.
std::optional<StageRecord> read_stage_record(const std::filesystem::path& dir);
// Written atomically, once the folder's frames are on disk.
void write_stage_record(const std::filesystem::path& dir, const StageRecord& record);
// Says a reused record's warnings again (messages::warning; those already given are not repeated).
void repeat_warnings(const std::optional<StageRecord>& record);
// `earlier`'s warnings followed by those of `later` not among them.
std::vector<std::string> merged_warnings(const std::vector<std::string>& earlier, const std::vector<std::string>& later);
// Before a stage starts writing into `dir`: its record goes, so an interrupted run is never taken
// for a finished one.
void remove_stage_record(const std::filesystem::path& dir);

}  // namespace spume
