#pragma once
// Loading a scene: the JSON file (or a scene built from command-line options), with --set overrides
// applied, ready for the sim and render readers.
#include <filesystem>
#include <string>
#include <vector>

#include "sim/core/params.h"

namespace spume {

struct LoadedScene {
  ParamReader root;
  std::filesystem::path dir;   // relative paths in the scene resolve here
  std::string default_name;    // the file's stem
};

LoadedScene load_scene_file(const std::filesystem::path& path, const std::vector<std::string>& overrides);
LoadedScene scene_from_json(Json json, const std::string& source, const std::filesystem::path& dir,
                            const std::string& default_name, const std::vector<std::string>& overrides);

}  // namespace spume
