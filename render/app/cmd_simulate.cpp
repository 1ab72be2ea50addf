// spume simulate: the simulation stages on their own (fluid solver for solver scenes, then diffuse).
#include <cstdio>

#include "cli_args.h"
#include "commands.h"
#include "core/error.h"
#include "pipeline/simulate_scene.h"
#include "scene_args.h"

namespace spume {

int command_simulate(const std::vector<std::string>& raw) {
  std::vector<cli::OptionSpec> options = scene_command_options();
  options.push_back({"frames", true, false, "A-B       simulate only frames A to B, clamped to the scene's (diffuse material starts empty at A)"});
  options.push_back({"bgeo", false, false, "          also write the diffuse frames as BGEO (Houdini, Blender)"});
  options.push_back({"force", false, false, "          simulate even when the caches are current"});
  const cli::ParsedArgs args = cli::parse(raw, options, "simulate");
  const SceneSetup setup =
      load_scene_setup(args, options, "simulate", args.has("bgeo") ? std::vector<std::string>{"output.bgeo=true"}
                                                                   : std::vector<std::string>{});
  SimulateOptions sim;
  sim.out_root = setup.out_root;
  sim.quiet = setup.quiet;
  sim.force = args.has("force");
  if (auto frames = args.value("frames")) sim.frames = cli::parse_frame_range(*frames, "--frames");
  const SceneSimulation result = simulate_scene(setup.sim, sim);
  if (!setup.quiet) {
    if (result.fluid.reused) std::fprintf(stderr, "fluid: caches are current, solver not run\n");
    if (result.diffuse.reused) std::fprintf(stderr, "diffuse: caches are current, nothing simulated\n");
  }
  return 0;
}

}  // namespace spume
