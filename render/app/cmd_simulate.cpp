// spume simulate: the simulation stages on their own (fluid solver for solver scenes, then diffuse).
#include <cstdio>

#include "render/app/cli/cli_args.h"
#include "render/app/commands.h"
#include "sim/core/error.h"
#include "sim/stage/simulate_scene.h"
#include "render/app/scene/scene_args.h"
#include "render/app/scene/scene_fog.h"
#include "render/app/scene/scene_lock.h"

namespace spume {
namespace {

int simulate(const cli::ParsedArgs& args) {
  std::optional<std::pair<int, int>> frames;
  if (auto spec = args.value("frames")) frames = cli::parse_frame_range(*spec, "--frames");
  std::vector<std::string> overrides;
  if (args.has("bgeo")) overrides.push_back("output.bgeo=true");
  if (args.has("vdb")) overrides.push_back("output.vdb=true");
  const SceneSetup setup = load_scene_setup(args, overrides);
  check_fog_request(setup);
  DiffuseStageOptions sim;
  sim.out_root = setup.out_root;
  sim.quiet = setup.quiet;
  sim.force = args.has("force");
  if (frames) sim.frames = *frames;
  const auto lock = lock_scene_output(setup, OutputLock::Mode::Exclusive, "spume simulate");
  const SceneSimulation result = simulate_scene(setup.sim, sim);
  bring_fog_in_line(setup);  // the fog follows the caches just made, or goes with output.fog off
  if (!setup.quiet) {
    if (result.fluid.reused) std::fprintf(stderr, "fluid: caches are current, solver not run\n");
    if (result.diffuse.reused) std::fprintf(stderr, "diffuse: caches are current, nothing simulated\n");
    for (const auto& [folder, made] : result.exports)
      if (made.kept > 0 && made.written == 0 && made.removed == 0)
        std::fprintf(stderr, "%s: files are current, nothing written\n", folder.c_str());
  }
  return 0;
}

}  // namespace

Command cmd_simulate() {
  cli::CommandSpec spec;
  spec.name = "simulate";
  spec.forms = scene_command_forms();
  spec.summary = "fluid frames -> diffuse caches (spray, foam, bubbles); solver scenes: fluid first";
  spec.options = scene_command_options();
  spec.options.push_back(
      {"frames", "A-B", "simulate only frames A to B, clamped to the scene's (diffuse material starts empty at A)"});
  spec.options.push_back({"bgeo", "", "also write the diffuse frames as BGEO (Houdini)"});
  spec.options.push_back({"vdb", "", "also write the diffuse frames as OpenVDB points (Houdini)"});
  spec.options.push_back({"force", "", "simulate even when the caches are current"});
  return {spec, simulate};
}

}  // namespace spume
