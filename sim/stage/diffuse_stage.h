#pragma once
// The simulation stage of a run: fluid frames in, diffuse caches and statistics out, on disk.
//   OUT/<scene>/diffuse/diffuse_0000.spd   one cache per frame (io/spume_cache.h documents the format)
//   (output.bgeo, output.vdb: made from these caches afterwards, stage/stage_exports.h)
//   OUT/<scene>/stats.csv                  counts and milliseconds per stage, one row per frame
//   OUT/<scene>/diffuse_params.json        every diffuse parameter as used (defaults resolved)
#include <filesystem>
#include <optional>
#include <utility>
#include <vector>

#include "sim/io/cache_layout.h"
#include "sim/io/stage_record.h"
#include "sim/stage/scene_inputs.h"
#include "sim/io/fluid_source.h"
#include "sim/scene/sim_scene.h"

namespace spume {

struct DiffuseStageOptions {
  std::filesystem::path out_root = "out";
  std::optional<std::pair<int, int>> frames;  // inclusive; overrides the scene's range
  bool quiet = false;
  bool force = false;  // simulate even when the diffuse caches are current (cache_state.h)
};

struct DiffuseStageSummary {
  bool reused = false;  // the caches were current; nothing ran
  int frames = 0;  // frames simulated (or, reused, found current)
  size_t max_diffuse = 0;
  uint64_t generated = 0;
  double seconds = 0.0;
  std::filesystem::path out_dir;
  std::string why;  // when it ran: what made the caches stale
  int continued_from = -1;  // the frame a current shorter run was continued from, if one was
};


// The frames the stage covers: the source's frames within options.frames or else the scene's range.
std::vector<int> diffuse_frames_to_run(const SimScene& scene, const FluidSource& source,
                                       const DiffuseStageOptions& options);

// What the stage makes for `frames` (io/stage_record.h): the diffuse keys, the domain and tanks the
// inputs resolved to, each fluid frame's file, and the body track of dynamic solids.
StageRecord diffuse_stage_record(const SimScene& scene, const SceneInputs& inputs, const std::vector<int>& frames,
                                 const std::filesystem::path& scene_out);
// `needed_frames`: the frames whose caches must be on disk (cache_match); empty: all of `frames`.
RecordMatch diffuse_caches_match(const SimScene& scene, const SceneInputs& inputs, const std::vector<int>& frames,
                                 const std::filesystem::path& scene_out, const std::vector<int>& needed_frames = {});
// The caches run_diffuse_stage would make are on disk and current.
bool diffuse_caches_current(const SimScene& scene, const SceneInputs& inputs, const FluidSource& source,
                            const DiffuseStageOptions& options);

// `inputs`: read_scene_inputs of the scene (solids with an inferred tank, the domain).
DiffuseStageSummary run_diffuse_stage(const SimScene& scene, const SceneInputs& inputs, FluidSource& source,
                               const DiffuseStageOptions& options);

}  // namespace spume
