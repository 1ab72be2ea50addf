#include "scene_args.h"

#include "core/error.h"
#include "core/parallel.h"
#include "scene_file.h"

namespace spume {
namespace {

// The scene name for a bare file pattern: its file name without the frame placeholder.
std::string name_from_pattern(const std::string& pattern) {
  std::string stem = std::filesystem::path(pattern).filename().string();
  stem = stem.substr(0, stem.find_first_of("%#."));
  while (!stem.empty() && (stem.back() == '_' || stem.back() == '-')) stem.pop_back();
  return stem.empty() ? "fluid" : stem;
}

}  // namespace

std::vector<cli::OptionSpec> scene_command_options() {
  return {
      {"out", "DIR", "output root (default out/); results go to DIR/<scene name>/"},
      {"threads", "N", "worker threads (default: one per core); results do not depend on it"},
      {"set", "KEY=VALUE", "override a scene key by its path, e.g. --set diffuse.k_ta=2000", true},
      {"quiet", "", "no progress on stderr"},
      {"fluid", "PATTERN", "fluid files with every default, no scene file (e.g. 'cache/ParticleData_Fluid_%d.bgeo')"},
      {"radius", "R", "with --fluid: the fluid particle radius in m"},
      {"fps", "F", "with --fluid: frames per second of the fluid files (default 50)"},
  };
}

std::vector<std::string> scene_command_forms(const std::string& extra) {
  const std::string tail = (extra.empty() ? "" : extra + " ") + "[options]";
  return {"SCENE.json " + tail, "--fluid PATTERN --radius R " + tail};
}

SceneSetup load_scene_setup(const cli::ParsedArgs& args, const std::vector<std::string>& extra_overrides) {
  if (args.has("threads")) set_thread_count(cli::parse_int(*args.value("threads"), "--threads", 1, 1024));
  std::vector<std::string> overrides = args.all("set");
  overrides.insert(overrides.end(), extra_overrides.begin(), extra_overrides.end());
  LoadedScene loaded = [&] {
    if (args.has("fluid")) {
      if (!args.positional.empty())
        cli::usage_fail("give either a SCENE file (", args.positional[0], ") or --fluid, not both");
      if (!args.has("radius")) cli::usage_fail("--fluid needs --radius R (the fluid particle radius in m)");
      Json scene = {{"name", name_from_pattern(*args.value("fluid"))},
                    {"fluid",
                     {{"source", "files"},
                      {"files", *args.value("fluid")},
                      {"radius", cli::parse_double(*args.value("radius"), "--radius")},
                      {"fps", args.has("fps") ? cli::parse_double(*args.value("fps"), "--fps") : 50.0}}}};
      return scene_from_json(std::move(scene), "--fluid", ".", "fluid", overrides);
    }
    if (args.has("radius") || args.has("fps")) cli::usage_fail("--radius and --fps go with --fluid");
    if (args.positional.empty()) cli::usage_fail("no scene: give SCENE.json, or --fluid PATTERN --radius R");
    return load_scene_file(args.positional[0], overrides);
  }();

  SceneSetup setup;
  setup.sim = read_sim_scene(loaded.root, loaded.dir, loaded.default_name);
  setup.render = read_render_settings(loaded.root.child("render"), setup.sim.fluid.particle_radius);
  loaded.root.reject_unknown_keys();
  setup.render_keys = loaded.root.raw("render");
  if (auto out = args.value("out")) setup.out_root = *out;
  setup.quiet = args.has("quiet");
  return setup;
}

}  // namespace spume
