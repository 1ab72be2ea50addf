#include "simulate_scene.h"

namespace spume {

std::unique_ptr<FluidSource> scene_fluid_source(const SimScene& scene, const std::filesystem::path& out_root) {
  if (scene.source == FluidSourceKind::Solver)
    return make_file_source(fluid_cache_pattern(out_root / scene.name), scene.fluid.fps);
  return make_file_source(scene.file_pattern, scene.fluid.fps);
}

std::vector<int> scene_frames(const SimScene& scene) {
  if (scene.source == FluidSourceKind::Solver) {
    std::vector<int> frames;
    for (int f = scene.frames->first; f <= scene.frames->second; ++f) frames.push_back(f);
    return frames;
  }
  return diffuse_frames_to_run(scene, *make_file_source(scene.file_pattern, scene.fluid.fps), SimulateOptions{});
}

bool scene_simulation_is_current(const SimScene& scene, const SimulateOptions& options) {
  if (scene.source == FluidSourceKind::Solver && !fluid_caches_current(scene, options.out_root)) return false;
  const auto source = scene_fluid_source(scene, options.out_root);
  return diffuse_caches_current(scene, *source, options);
}

SceneSimulation simulate_scene(const SimScene& scene, const SimulateOptions& options, bool diffuse) {
  SceneSimulation result;
  if (scene.source == FluidSourceKind::Solver) {
    FluidStageOptions fluid_options;
    fluid_options.out_root = options.out_root;
    fluid_options.quiet = options.quiet;
    fluid_options.force = options.force;
    result.fluid = run_fluid_stage(scene, fluid_options);
  }
  if (diffuse) {
    auto source = scene_fluid_source(scene, options.out_root);
    SimulateOptions diffuse_options = options;
    // New fluid frames make the diffuse caches stale even when the keys did not change.
    diffuse_options.force = options.force || (result.fluid.frames > 0 && !result.fluid.reused);
    const SceneInputs inputs = read_scene_inputs(scene, options.out_root, options.quiet);
    result.diffuse = run_simulation(scene, inputs, *source, diffuse_options);
  }
  return result;
}

}  // namespace spume
