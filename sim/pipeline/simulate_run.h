#pragma once
// The simulation stage of a run: fluid frames in, diffuse caches and statistics out, on disk.
//   OUT/<scene>/diffuse/diffuse_0000.spd   one cache per frame (io/spume_cache.h documents the format)
//   OUT/<scene>/diffuse_bgeo/...           the same as BGEO, when asked for
//   OUT/<scene>/stats.csv                  counts and milliseconds per stage, one row per frame
//   OUT/<scene>/diffuse_params.json        every diffuse parameter as used (defaults resolved)
#include <filesystem>
#include <optional>
#include <utility>

#include "scene/fluid_source.h"
#include "scene/sim_scene.h"

namespace spume {

struct SimulateOptions {
  std::filesystem::path out_root = "out";
  std::optional<std::pair<int, int>> frames;  // inclusive; overrides the scene's range
  bool quiet = false;
};

struct SimulateSummary {
  int frames = 0;
  size_t max_diffuse = 0;
  uint64_t generated = 0;
  double seconds = 0.0;
  std::filesystem::path out_dir;
};

std::filesystem::path diffuse_cache_path(const std::filesystem::path& scene_out, int frame);

SimulateSummary run_simulation(const SimScene& scene, FluidSource& source, const SimulateOptions& options);

}  // namespace spume
