#include "render/app/scene/scene_file.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "render/app/cli/cli_args.h"
#include "sim/core/error.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

// "a directory, not a scene file" and, when there are a few, the scenes it holds: the usual slip is
// `spume run scenes/` for `spume run scenes/wave.json`.
[[noreturn]] void fail_directory(const fs::path& path) {
  constexpr size_t kListed = 8;
  std::vector<std::string> scenes;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(path, ec))
    if (entry.path().extension() == ".json") scenes.push_back(entry.path().filename().string());
  std::sort(scenes.begin(), scenes.end());
  std::string listing;
  if (scenes.empty()) listing = "; it holds no .json file";
  else if (scenes.size() <= kListed) {
    listing = "; scene files in it:";
    for (const auto& name : scenes) listing += str(" ", (path / name).string());
  } else {
    listing = str("; it holds ", scenes.size(), " .json files, e.g. ", (path / scenes.front()).string());
  }
  fail(path.string(), ": is a directory, not a scene file (give one SCENE.json)", listing);
}

}  // namespace

LoadedScene scene_from_json(Json json, const std::string& source, const std::filesystem::path& dir,
                            const std::string& default_name, const std::vector<std::string>& overrides) {
  // Overrides come from the command line (--set, --vary): a malformed one is a usage error.
  for (const auto& o : overrides) cli::as_usage([&] { apply_override(json, o); });
  return LoadedScene{ParamReader::from_json(std::move(json), source), dir, default_name};
}

LoadedScene load_scene_file(const std::filesystem::path& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail_directory(path);
  std::ifstream in(path);
  if (!in)
    fail(path.string(), ": cannot open the scene file (", fs::exists(path, ec) ? "unreadable" : "no such file", ")");
  std::stringstream text;
  text << in.rdbuf();
  Json json = parse_json_text(text.str(), path.string());
  return scene_from_json(std::move(json), path.string(), path.parent_path(), path.stem().string(), overrides);
}

}  // namespace spume
