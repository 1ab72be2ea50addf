#include "sim/stage/simulate_scene.h"

#include "sim/io/cache_layout.h"

namespace spume {

std::unique_ptr<FluidSource> scene_fluid_source(const SimScene& scene, const std::filesystem::path& out_root) {
  if (scene.source == FluidSourceKind::Solver)
    return make_file_source(fluid_cache_pattern(out_root / scene.name), scene.fluid.fps);
  return make_file_source(scene.file_pattern, scene.fluid.fps, scene.allow_gaps, scene.velocity_scale, scene.read);
}

std::vector<int> scene_frames(const SimScene& scene) {
  if (scene.source == FluidSourceKind::Solver) {
    std::vector<int> frames;
    for (int f = scene.frames->first; f <= scene.frames->second; ++f) frames.push_back(f);
    return frames;
  }
  return diffuse_frames_to_run(scene, *make_file_source(scene.file_pattern, scene.fluid.fps, scene.allow_gaps, scene.velocity_scale, scene.read),
                               DiffuseStageOptions{});
}

namespace {

// The last fluid frame a run needs: the end of the asked range, not the scene's.
FluidStageOptions fluid_options(const SimScene& scene, const DiffuseStageOptions& options) {
  FluidStageOptions o;
  o.out_root = options.out_root;
  o.quiet = options.quiet;
  o.force = options.force;
  if (options.frames) o.last_frame = options.frames->second;
  (void)scene;
  return o;
}

}  // namespace

bool scene_simulation_is_current(const SimScene& scene, const DiffuseStageOptions& options) {
  if (scene.source == FluidSourceKind::Solver) {
    const int last = fluid_stage_last_frame(scene, fluid_options(scene, options));
    if (fluid_caches_match(scene, options.out_root, last).kind != RecordMatch::Kind::Current) return false;
  }
  const auto source = scene_fluid_source(scene, options.out_root);
  const SceneInputs inputs = read_scene_inputs(scene, options.out_root, true);
  if (!diffuse_caches_current(scene, inputs, *source, options)) return false;
  const std::filesystem::path scene_out = options.out_root / scene.name;
  if (scene.source == FluidSourceKind::Solver) {
    const std::vector<int> frames = recorded_frames(fluid_cache_path(scene_out, 0).parent_path(), {});
    for (const FrameExport& e : fluid_exports(scene, scene_out))
      if (!export_current(e, frames, scene_out)) return false;
  }
  const std::vector<int> frames = recorded_frames(diffuse_cache_path(scene_out, 0).parent_path(),
                                                  diffuse_frames_to_run(scene, *source, options));
  for (const FrameExport& e : diffuse_exports(scene, scene_out))
    if (!export_current(e, frames, scene_out)) return false;
  return true;
}

SceneSimulation simulate_scene(const SimScene& scene, const DiffuseStageOptions& options, bool diffuse) {
  SceneSimulation result;
  const std::filesystem::path scene_out = options.out_root / scene.name;
  if (scene.source == FluidSourceKind::Solver) {
    result.fluid = run_fluid_stage(scene, fluid_options(scene, options));
    const std::vector<int> frames = recorded_frames(fluid_cache_path(scene_out, 0).parent_path(), {});
    for (const FrameExport& e : fluid_exports(scene, scene_out))
      result.exports.emplace_back(e.folder, bring_export_in_line(e, frames, scene_out, options.quiet));
  }
  if (diffuse) {
    auto source = scene_fluid_source(scene, options.out_root);
    const SceneInputs inputs = read_scene_inputs(scene, options.out_root, options.quiet);
    // New fluid frames have new file identities, which the diffuse record compares (io/stage_record.h).
    result.diffuse = run_diffuse_stage(scene, inputs, *source, options);
    // The frames the caches hold by their record: a reused run over a part of them keeps the rest.
    const std::vector<int> frames = recorded_frames(diffuse_cache_path(scene_out, 0).parent_path(),
                                                    diffuse_frames_to_run(scene, *source, options));
    for (const FrameExport& e : diffuse_exports(scene, scene_out))
      result.exports.emplace_back(e.folder, bring_export_in_line(e, frames, scene_out, options.quiet));
  }
  return result;
}

}  // namespace spume
