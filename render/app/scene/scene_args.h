#pragma once
// What simulate, render and run share on the command line: the scene (a file, or --fluid PATTERN
// --radius R with every default), --set overrides, the output root, threads and quiet, read into the
// sim and render halves of the scene. Unknown scene keys are rejected after both halves are read.
#include <filesystem>
#include <string>
#include <vector>

#include "render/app/cli/cli_args.h"
#include "render/frame/render_settings.h"
#include "sim/scene/sim_scene.h"

namespace spume {

// The options every scene command takes; commands append their own.
std::vector<cli::OptionSpec> scene_command_options();

// The usage lines of a scene command: with a scene file, or with --fluid.
std::vector<std::string> scene_command_forms(const std::string& extra = "");

struct SceneSetup {
  SimScene sim;
  RenderSettings render;
  Json render_keys;                // the render keys' values as used, defaults included (frame records)
  std::filesystem::path out_root = "out";
  bool quiet = false;
};

// Applies --threads, loads the scene with --set (and `extra_overrides`), reads both halves. Command-line
// mistakes throw cli::UsageError, problems of the scene spume::Error.
SceneSetup load_scene_setup(const cli::ParsedArgs& args, const std::vector<std::string>& extra_overrides = {});

}  // namespace spume
