#include "scene_file.h"

#include <fstream>
#include <sstream>

#include "core/error.h"

namespace spume {

LoadedScene scene_from_json(Json json, const std::string& source, const std::filesystem::path& dir,
                            const std::string& default_name, const std::vector<std::string>& overrides) {
  for (const auto& o : overrides) apply_override(json, o);
  return LoadedScene{ParamReader::from_json(std::move(json), source), dir, default_name};
}

LoadedScene load_scene_file(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path);
  if (!in) fail(path.string(), ": cannot open the scene file (", std::filesystem::exists(path) ? "unreadable" : "no such file", ")");
  std::stringstream text;
  text << in.rdbuf();
  Json json;
  try {
    json = Json::parse(text.str(), nullptr, true, /*ignore_comments=*/true);
  } catch (const Json::parse_error& e) {
    // e.byte is the offset of the error; turn it into a line number for the message.
    const std::string s = text.str();
    const size_t upto = std::min<size_t>(e.byte, s.size());
    const long line = 1 + std::count(s.begin(), s.begin() + long(upto), '\n');
    fail(path.string(), ":", line, ": not valid JSON: ", e.what());
  }
  return scene_from_json(std::move(json), path.string(), path.parent_path(), path.stem().string(), overrides);
}

}  // namespace spume
