// spume render: the simulation caches -> PNG frames (never simulates), and spume run: simulate what is
// missing, then render.
#include <cstdio>

#include <limits>

#include "render/app/cli/cli_args.h"
#include "sim/core/frame_spec.h"
#include "render/app/commands.h"
#include "sim/core/error.h"
#include "sim/stage/simulate_scene.h"
#include "render/app/movie.h"
#include "render/app/scene/scene_render.h"
#include "render/stage/render_stage.h"
#include "render/app/scene/scene_args.h"
#include "render/app/scene/scene_fog.h"
#include "render/app/scene/scene_lock.h"

namespace spume {
namespace {

std::vector<cli::OptionSpec> render_options() {
  std::vector<cli::OptionSpec> options = scene_command_options();
  options.push_back({"frames", "SPEC", "render only these frames: 7, 0-99, 0-99:2, 1-3,5,10-20"});
  options.push_back({"overwrite", "", "render frames that already exist on disk"});
  options.push_back({"movie", "", "also encode OUT/<scene>/<scene>.mp4 with ffmpeg (if installed)"});
  options.push_back({"fog", "VOXEL", "also write the diffuse frames as OpenVDB fog volumes with voxels of VOXEL m "
                                     "(output.fog)"});
  options.push_back({"exr", "", "also write each frame as multilayer OpenEXR beside its PNG (render.exr)"});
  return options;
}

// The render stage over the frames --frames selects, once the caches they need are found current.
RenderStageSummary render_frames(const cli::ParsedArgs& args, const SceneSetup& setup) {
  SceneRender scene = scene_render(setup.sim, setup.out_root);
  print_input_warnings(scene);
  PreparedRender prepared = prepare_render(scene.scene, setup.render);
  const std::vector<int> frames = frames_to_render(scene.scene, args.value("frames"));
  check_diffuse_caches(setup.sim, scene, prepared.settings, frames);
  RenderStageOptions o;
  o.quiet = setup.quiet;
  o.overwrite = args.has("overwrite");
  const RenderStageSummary summary = run_render_stage(prepared, setup.render_keys, frames, o);
  bring_fog_in_line(setup);
  return summary;
}

void report(const char* what, bool ran, bool quiet) {
  if (!quiet) std::fprintf(stderr, "  %-22s %s\n", what, ran ? "ran" : "skipped");
}

void finish_render(const RenderStageSummary& s, const cli::ParsedArgs& args, const SceneSetup& setup) {
  if (!setup.quiet) {
    std::fprintf(stderr, "render: %d frames written, %d current on disk, %.1f s\n", s.written, s.skipped, s.seconds);
    if (s.exr_removed > 0) std::fprintf(stderr, "render: removed %d EXR frames of an earlier run (render.exr is off)\n", s.exr_removed);
    if (s.stale_elsewhere > 0)
      std::fprintf(stderr, "render: %d other frames on disk are stale for the current keys or caches (not rendered: "
                   "outside --frames)\n", s.stale_elsewhere);
    for (const auto& stage : s.stages) std::fprintf(stderr, "  ran: %s\n", stage.c_str());
  }
  if (args.has("movie") && s.first_frame_number >= 0) {
    const auto scene_out = setup.out_root / setup.sim.name;
    const auto movie = scene_out / (setup.sim.name + ".mp4");
    write_movie((scene_out / setup.render.frame_pattern).string(), s.first_frame_number, setup.sim.fluid.fps, movie,
                setup.quiet);
    if (!setup.quiet) std::printf("Saved: %s\n", movie.string().c_str());
  }
}

// The export flags as the keys they stand for.
std::vector<std::string> export_overrides(const cli::ParsedArgs& args) {
  std::vector<std::string> keys;
  if (auto voxel = args.value("fog")) keys.push_back("output.fog=" + *voxel);
  if (args.has("exr")) keys.push_back("render.exr=true");
  return keys;
}

int render(const cli::ParsedArgs& args) {
  if (auto frames = args.value("frames")) cli::check_frame_spec(*frames, "--frames");
  const SceneSetup setup = load_scene_setup(args, export_overrides(args));
  check_fog_request(setup);
  const auto lock = lock_scene_output(setup, OutputLock::Mode::Shared, "spume render");
  finish_render(render_frames(args, setup), args, setup);
  return 0;
}

int run(const cli::ParsedArgs& args) {
  if (auto frames = args.value("frames")) cli::check_frame_spec(*frames, "--frames");
  const SceneSetup setup = load_scene_setup(args, export_overrides(args));
  check_fog_request(setup);
  DiffuseStageOptions sim;
  sim.out_root = setup.out_root;
  sim.quiet = setup.quiet;
  sim.force = args.has("force");
  // The simulation starts at the scene's first frame whatever is rendered, and runs only as far as
  // the last frame asked for (a later, longer run continues from there).
  if (auto spec = args.value("frames")) {
    const std::vector<int> asked = parse_frame_spec(*spec, 0, std::numeric_limits<int>::max(), "--frames");
    sim.frames = std::make_pair(setup.sim.frames ? setup.sim.frames->first : 0, asked.back());
  }
  const bool diffuse = setup.render.draws_diffuse();
  auto lock = lock_scene_output(setup, OutputLock::Mode::Exclusive, "spume run");
  const SceneSimulation simulated = simulate_scene(setup.sim, sim, diffuse);
  lock.reset();  // the render shares the folder with renders of the same keys
  lock = lock_scene_output(setup, OutputLock::Mode::Shared, "spume run");
  if (!setup.quiet) {
    std::fprintf(stderr, "stages of %s:\n", setup.sim.name.c_str());
    if (setup.sim.source == FluidSourceKind::Solver)
      report("fluid solver", !simulated.fluid.reused, false);
    report("diffuse simulation", diffuse && !simulated.diffuse.reused, false);
  }
  finish_render(render_frames(args, setup), args, setup);
  return 0;
}

}  // namespace

Command cmd_render() {
  cli::CommandSpec spec;
  spec.name = "render";
  spec.forms = scene_command_forms();
  spec.summary = "the simulation caches -> PNG frames (never simulates)";
  spec.options = render_options();
  return {spec, render};
}

Command cmd_run() {
  cli::CommandSpec spec;
  spec.name = "run";
  spec.forms = scene_command_forms();
  spec.summary = "simulate what is missing (fluid, then diffuse), then render the PNG frames";
  spec.options = render_options();
  spec.options.push_back({"force", "", "simulate even when the caches are current"});
  return {spec, run};
}

}  // namespace spume
