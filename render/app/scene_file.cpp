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
  Json json = parse_json_text(text.str(), path.string());
  return scene_from_json(std::move(json), path.string(), path.parent_path(), path.stem().string(), overrides);
}

}  // namespace spume
