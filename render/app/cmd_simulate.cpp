// spume simulate: fluid frames -> diffuse caches (the simulation stage on its own).
#include <cstdio>
#include <filesystem>

#include "cli_args.h"
#include "commands.h"
#include "core/error.h"
#include "core/parallel.h"
#include "pipeline/simulate_run.h"
#include "scene/sim_scene.h"
#include "scene_file.h"

namespace spume {
namespace {

const std::vector<cli::OptionSpec> kOptions = {
    {"out", true, false, "DIR       output root (default out/); results go to DIR/<scene name>/"},
    {"frames", true, false, "A-B       simulate only frames A to B (diffuse material starts empty at A)"},
    {"threads", true, false, "N         worker threads (default: one per core); results do not depend on it"},
    {"set", true, true, "KEY=VALUE override a scene key by its path, e.g. --set diffuse.k_ta=2000"},
    {"quiet", false, false, "          no progress on stderr"},
    {"bgeo", false, false, "          also write the diffuse frames as BGEO (Houdini, Blender)"},
    {"fluid", true, false, "PATTERN   run on fluid files with every default, no scene file (e.g. 'cache/ParticleData_Fluid_%d.bgeo')"},
    {"radius", true, false, "R         with --fluid: the fluid particle radius in m"},
    {"fps", true, false, "F         with --fluid: frames per second of the fluid files (default 50)"},
};

// The scene name for a bare file pattern: its file name without the frame placeholder.
std::string name_from_pattern(const std::string& pattern) {
  std::string stem = std::filesystem::path(pattern).filename().string();
  stem = stem.substr(0, stem.find_first_of("%#."));
  while (!stem.empty() && (stem.back() == '_' || stem.back() == '-')) stem.pop_back();
  return stem.empty() ? "fluid" : stem;
}

}  // namespace

int command_simulate(const std::vector<std::string>& raw) {
  const cli::ParsedArgs args = cli::parse(raw, kOptions, "simulate");
  if (args.has("threads")) set_thread_count(cli::parse_int(*args.value("threads"), "--threads", 1, 1024));

  std::vector<std::string> overrides = args.all("set");
  if (args.has("bgeo")) overrides.push_back("output.bgeo=true");
  LoadedScene loaded = [&] {
    if (args.has("fluid")) {
      if (!args.positional.empty()) fail("spume simulate: give either a SCENE file or --fluid, not both");
      if (!args.has("radius")) fail("spume simulate --fluid: --radius R (the fluid particle radius in m) is required");
      Json scene = {{"name", name_from_pattern(*args.value("fluid"))},
                    {"fluid",
                     {{"source", "files"},
                      {"files", *args.value("fluid")},
                      {"radius", cli::parse_double(*args.value("radius"), "--radius")},
                      {"fps", args.has("fps") ? cli::parse_double(*args.value("fps"), "--fps") : 50.0}}}};
      return scene_from_json(std::move(scene), "--fluid", ".", "fluid", overrides);
    }
    if (args.positional.size() != 1)
      fail("usage: spume simulate SCENE.json [options]  |  spume simulate --fluid PATTERN --radius R [options]\n",
           cli::usage_lines(kOptions));
    return load_scene_file(args.positional[0], overrides);
  }();

  const SimScene scene = read_sim_scene(loaded.root, loaded.dir, loaded.default_name);
  loaded.root.reject_unknown_keys();

  SimulateOptions options;
  if (auto out = args.value("out")) options.out_root = *out;
  if (auto frames = args.value("frames")) options.frames = cli::parse_frame_range(*frames, "--frames");
  options.quiet = args.has("quiet");

  if (scene.source != FluidSourceKind::Files)
    fail(loaded.root.source(), ": /fluid/source: \"solver\" is not available in this build yet; use \"files\"");
  auto source = make_file_source(scene.file_pattern, scene.fluid.fps);
  run_simulation(scene, *source, options);
  return 0;
}

}  // namespace spume
