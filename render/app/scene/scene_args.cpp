#include "render/app/scene/scene_args.h"

#include <algorithm>
#include <cctype>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/keys/scene_keys.h"
#include "render/app/scene/scene_file.h"

namespace spume {
namespace {

// The scene name for a bare file pattern: its file name without the frame placeholder (read_sim_scene
// makes it usable as a folder name, and says so).
std::string name_from_pattern(const std::string& pattern) {
  std::string stem = std::filesystem::path(pattern).filename().string();
  stem = stem.substr(0, stem.find_first_of("%#.$"));
  while (!stem.empty() && (stem.back() == '_' || stem.back() == '-')) stem.pop_back();
  return stem.empty() ? "fluid" : stem;
}

// What --tank asks for: a tank inferred from the fluid, none, or one given by its corners.
struct TankOption {
  enum class Kind { Auto, None, Corners } kind = Kind::Auto;
  Json solid;  // Auto, Corners: the scene's "solids" entry
};

// --tank auto, none (either in any case, spaces around ignored), or the six corner coordinates
// "x0,y0,z0,x1,y1,z1" of an open tank.
TankOption tank_from_option(const std::string& text) {
  const size_t b = text.find_first_not_of(" \t"), e = text.find_last_not_of(" \t");
  std::string word = b == std::string::npos ? "" : text.substr(b, e - b + 1);
  std::transform(word.begin(), word.end(), word.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (word == "auto") return {TankOption::Kind::Auto, {{"type", "tank"}, {"infer", true}}};
  if (word == "none") return {TankOption::Kind::None, nullptr};
  const std::string expected = str("--tank \"", text, "\": expected auto, none or six numbers x0,y0,z0,x1,y1,z1 (the tank's "
                                   "corners in m)");
  std::vector<double> v;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    try {
      v.push_back(cli::parse_double(part, "--tank"));
    } catch (const cli::UsageError&) {
      cli::usage_fail(expected, "; \"", part, "\" is not a number");
    }
    start = comma + 1;
  }
  if (v.size() != 6) cli::usage_fail(expected, ", found ", v.size(), v.size() == 1 ? " number" : " numbers");
  return {TankOption::Kind::Corners, {{"type", "tank"}, {"min", {v[0], v[1], v[2]}}, {"max", {v[3], v[4], v[5]}}}};
}

}  // namespace

std::vector<cli::OptionSpec> scene_command_options() {
  return {
      {"out", "DIR", "output root (default out/); results go to DIR/<scene name>/"},
      {"threads", "N", "worker threads (default: one per core); results do not depend on it"},
      {"set", "KEY=VALUE", "override a scene key by its path, e.g. --set diffuse.k_ta=2000", true},
      cli::quiet_option(),
      {"fluid", "PATTERN", "fluid files with every default, no scene file (e.g. 'cache/ParticleData_Fluid_%d.bgeo')"},
      {"radius", "R", "with --fluid: the fluid particle radius in m"},
      {"fps", "F", "with --fluid: frames per second of the fluid files (default: fluid.fps's)"},
      {"tank", "auto|none|X0,Y0,Z0,X1,Y1,Z1",
       "with --fluid: the container, inferred from the fluid (auto), none, or its corners in m; open at the top. "
       "Without it, the inferred tank is used when the fluid was seen stopped at a floor and four walls (the log says)"},
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
      Json scene = {{"fluid",
                     {{"source", "files"},
                      {"files", *args.value("fluid")},
                      {"radius", cli::parse_double(*args.value("radius"), "--radius")}}}};
      // Without --fps the key is absent, so a cache that measures its own rate (a Mantaflow config) gives it.
      if (args.has("fps")) scene["fluid"]["fps"] = cli::parse_double(*args.value("fps"), "--fps");
      if (auto tank = args.value("tank")) {
        const TankOption option = tank_from_option(*tank);
        if (option.kind != TankOption::Kind::None) scene["solids"] = Json::array({option.solid});
      }
      return scene_from_json(std::move(scene), "--fluid", ".", name_from_pattern(*args.value("fluid")), overrides);
    }
    if (args.has("radius") || args.has("fps") || args.has("tank"))
      cli::usage_fail("--radius, --fps and --tank go with --fluid (a scene file lists its tank under \"solids\")");
    if (args.positional.empty()) cli::usage_fail("no scene: give SCENE.json, or --fluid PATTERN --radius R");
    return load_scene_file(args.positional[0], overrides);
  }();

  SceneSetup setup;
  setup.sim = read_sim_scene(loaded.root, loaded.dir, loaded.default_name);
  // The one-line run of fluid files without --tank (nor solids set with --set): the container the
  // fluid shows, when it shows one (scene/container.h); the log says which walls and why, or why none.
  if (args.has("fluid") && !args.has("tank") && setup.sim.source == FluidSourceKind::Files &&
      setup.sim.solids.empty() && setup.sim.infer_container == TankInference::Off)
    setup.sim.infer_container = TankInference::IfEvident;
  setup.render = read_render_settings(loaded.root.child("render"), setup.sim.fluid.particle_radius);
  loaded.root.reject_unknown_keys();
  setup.render_keys = loaded.root.effective("render");
  if (auto out = args.value("out")) setup.out_root = *out;
  setup.quiet = args.has("quiet");
  return setup;
}

}  // namespace spume
