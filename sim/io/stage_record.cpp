#include "sim/io/stage_record.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/core/messages.h"

namespace spume {
namespace {

using Json = nlohmann::json;

std::filesystem::path record_path(const std::filesystem::path& dir) { return dir / "record.json"; }

Json identity_json(const FileIdentity& id) { return Json::array({id.size, id.mtime_ns, id.crc}); }
FileIdentity identity_from(const Json& j) {
  return {j.at(0).get<uint64_t>(), j.at(1).get<int64_t>(), j.at(2).get<uint32_t>()};
}

std::string shown(const Json& j) {
  if (j.is_null()) return "absent";
  std::string text = j.dump();
  return text.size() > 80 ? text.substr(0, 77) + "..." : text;
}

}  // namespace

Json StageRecord::to_json() const {
  Json frames = Json::object(), others = Json::object();
  for (const auto& [frame, id] : frame_inputs) frames[std::to_string(frame)] = identity_json(id);
  for (const auto& [name, id] : other_inputs) others[name] = identity_json(id);
  Json j = {{"stage", stage}, {"keys", keys},       {"first_frame", first_frame}, {"last_frame", last_frame},
            {"frame_inputs", frames}, {"other_inputs", others}};
  if (!warnings.empty()) j["warnings"] = warnings;
  return j;
}

StageRecord StageRecord::from_json(const Json& j) {
  try {
    StageRecord r;
    r.stage = j.at("stage").get<std::string>();
    r.keys = j.at("keys");
    r.first_frame = j.at("first_frame").get<int>();
    r.last_frame = j.at("last_frame").get<int>();
    for (const auto& [frame, id] : j.at("frame_inputs").items()) r.frame_inputs[std::stoi(frame)] = identity_from(id);
    for (const auto& [name, id] : j.at("other_inputs").items()) r.other_inputs[name] = identity_from(id);
    if (j.contains("warnings")) r.warnings = j.at("warnings").get<std::vector<std::string>>();
    return r;
  } catch (const std::exception& e) {
    fail("malformed stage record: ", e.what());
  }
}

std::string json_difference(const Json& before, const Json& now, const std::string& path) {
  if (before == now) return "";
  const std::string here = path.empty() ? "(the whole value)" : path;
  if (before.is_object() && now.is_object()) {
    for (const auto& [key, value] : before.items()) {
      const std::string at = path.empty() ? key : path + "." + key;
      if (!now.contains(key)) return str(at, ": ", shown(value), " -> absent");
      if (std::string d = json_difference(value, now.at(key), at); !d.empty()) return d;
    }
    for (const auto& [key, value] : now.items())
      if (!before.contains(key)) return str(path.empty() ? key : path + "." + key, ": absent -> ", shown(value));
  }
  if (before.is_array() && now.is_array() && before.size() == now.size())
    for (size_t i = 0; i < before.size(); ++i)
      if (std::string d = json_difference(before[i], now[i], str(path, "[", i, "]")); !d.empty()) return d;
  return str(here, ": ", shown(before), " -> ", shown(now));
}

RecordMatch match_records(const StageRecord& made, const StageRecord& wanted) {
  auto stale = [](std::string why) { return RecordMatch{RecordMatch::Kind::Stale, std::move(why)}; };
  if (made.stage != wanted.stage) return stale(str("made by the ", made.stage, " stage"));
  if (std::string d = json_difference(made.keys, wanted.keys); !d.empty()) return stale(str("key ", d));
  if (made.first_frame != wanted.first_frame)
    return stale(str("made from frame ", made.first_frame, " on, now from frame ", wanted.first_frame));
  for (const auto& [name, id] : wanted.other_inputs) {
    auto it = made.other_inputs.find(name);
    if (it == made.other_inputs.end()) return stale(str(name, ": not read before"));
    if (!(it->second == id)) return stale(str(name, " changed (was ", it->second.text(), ", now ", id.text(), ")"));
  }
  for (const auto& [frame, id] : wanted.frame_inputs) {
    if (frame > made.last_frame) break;
    auto it = made.frame_inputs.find(frame);
    if (it == made.frame_inputs.end()) return stale(str("input of frame ", frame, " not read before"));
    if (!(it->second == id))
      return stale(str("the input file of frame ", frame, " changed (was ", it->second.text(), ", now ", id.text(), ")"));
  }
  if (made.last_frame >= wanted.last_frame) return {RecordMatch::Kind::Current, ""};
  return {RecordMatch::Kind::Prefix, str("made up to frame ", made.last_frame)};
}

std::string record_digest(const Json& j) {
  uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : j.dump()) hash = (hash ^ c) * 1099511628211ull;
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::optional<StageRecord> read_stage_record(const std::filesystem::path& dir) {
  std::ifstream in(record_path(dir));
  if (!in) return std::nullopt;
  try {
    return StageRecord::from_json(Json::parse(in));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

void write_stage_record(const std::filesystem::path& dir, const StageRecord& record) {
  write_file_atomically(record_path(dir), [&](std::ostream& out) { out << record.to_json().dump(1) << '\n'; });
}

void remove_stage_record(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  std::filesystem::remove(record_path(dir), ec);
  if (std::filesystem::exists(record_path(dir)))
    fail(record_path(dir).string(), ": cannot remove the stale record: ", ec.message());
  // Records of earlier spume versions would otherwise be mistaken for finished folders by them.
  std::filesystem::remove(dir / "fingerprint.json", ec);
}

void repeat_warnings(const std::optional<StageRecord>& record) {
  if (record)
    for (const std::string& w : record->warnings) messages::warning(w);
}

std::vector<std::string> merged_warnings(const std::vector<std::string>& earlier, const std::vector<std::string>& later) {
  std::vector<std::string> all = earlier;
  for (const std::string& w : later)
    if (std::find(all.begin(), all.end(), w) == all.end()) all.push_back(w);
  return all;
}

}  // namespace spume
