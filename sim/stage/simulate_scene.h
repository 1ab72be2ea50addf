#pragma once
// Both simulation stages of a scene, each skipped when its caches are current:
//   fluid   (solver scenes only) -> OUT/<scene>/fluid/      fluid_stage.h
//   diffuse                      -> OUT/<scene>/diffuse/    diffuse_stage.h
//   then the exports of each stage's caches (output.*: BGEO, OpenVDB points)    stage_exports.h
#include <memory>

#include "sim/stage/fluid_stage.h"
#include "sim/stage/diffuse_stage.h"
#include "sim/stage/stage_exports.h"

namespace spume {

struct SceneSimulation {
  FluidStageSummary fluid;     // frames == 0 when the fluid comes from files
  DiffuseStageSummary diffuse;     // frames == 0 when the diffuse stage was not asked for
  // The exports brought in line after the stages ran, by folder ("diffuse_vdb"): stage_exports.h.
  std::vector<std::pair<std::string, FrameExportSummary>> exports;
};

// Where the scene's fluid frames are read from: its files, or the solver's caches under out_root.
std::unique_ptr<FluidSource> scene_fluid_source(const SimScene& scene, const std::filesystem::path& out_root);

// The frames the diffuse stage and the renderer cover, known before any cache exists (a solver
// scene's range, or the fluid files found within the scene's range), so farms can plan chunks.
std::vector<int> scene_frames(const SimScene& scene);

// Both stages' caches are current for `options.out_root` and `options.frames`: simulate_scene would
// run nothing. Reads only fingerprints and directory listings.
bool scene_simulation_is_current(const SimScene& scene, const DiffuseStageOptions& options);

// `diffuse`: false leaves the diffuse stage out (a scene that draws no diffuse material).
SceneSimulation simulate_scene(const SimScene& scene, const DiffuseStageOptions& options, bool diffuse = true);

}  // namespace spume
