#include "scene_args.h"

#include "core/error.h"
#include "core/parallel.h"
#include "keys/scene_keys.h"
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

// --tank auto, or the six corner coordinates "x0,y0,z0,x1,y1,z1" of an open tank.
Json tank_from_option(const std::string& text) {
  if (text == "auto") return {{"type", "tank"}, {"infer", true}};
  std::vector<double> v;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    v.push_back(cli::parse_double(text.substr(start, comma - start), "--tank"));
    start = comma + 1;
  }
  if (v.size() != 6)
    cli::usage_fail("--tank \"", text, "\": expected auto or six numbers x0,y0,z0,x1,y1,z1 (m), found ", v.size());
  return {{"type", "tank"}, {"min", {v[0], v[1], v[2]}}, {"max", {v[3], v[4], v[5]}}};
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
      {"fps", "F", "with --fluid: frames per second of the fluid files (default: fluid.fps's)"},
      {"tank", "auto|X0,Y0,Z0,X1,Y1,Z1",
       "with --fluid: the container, inferred from the fluid (auto) or its corners in m; open at the top"},
      {"allow-gaps", "", "frames missing from the fluid files are interpolated between their neighbours"},
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
  if (args.has("allow-gaps")) overrides.push_back("fluid.allow_gaps=true");
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
                      {"fps", args.has("fps") ? cli::parse_double(*args.value("fps"), "--fps") : keys::fluid::fps.value[0]}}}};
      if (auto tank = args.value("tank")) scene["solids"] = Json::array({tank_from_option(*tank)});
      return scene_from_json(std::move(scene), "--fluid", ".", "fluid", overrides);
    }
    if (args.has("radius") || args.has("fps") || args.has("tank"))
      cli::usage_fail("--radius, --fps and --tank go with --fluid (a scene file lists its tank under \"solids\")");
    if (args.positional.empty()) cli::usage_fail("no scene: give SCENE.json, or --fluid PATTERN --radius R");
    return load_scene_file(args.positional[0], overrides);
  }();

  SceneSetup setup;
  setup.sim = read_sim_scene(loaded.root, loaded.dir, loaded.default_name);
  setup.render = read_render_settings(loaded.root.child("render"), setup.sim.fluid.particle_radius);
  loaded.root.reject_unknown_keys();
  setup.render_keys = loaded.root.effective("render");
  if (auto out = args.value("out")) setup.out_root = *out;
  setup.quiet = args.has("quiet");
  return setup;
}

}  // namespace spume
