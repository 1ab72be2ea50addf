#pragma once
// Where a scene's outputs live under OUT/<scene>/ (`scene_out`), in one place: both the simulation
// stages that write them and the renderer that reads them link this library.
//   fluid/fluid_0000.spf      solver scenes: the fluid per frame        fluid/record.json
//   fluid/restart_0000.spr    the solver's state at the last frame      fluid/bodies.csv
//   diffuse/diffuse_0000.spd, diffuse/record.json
//   fluid_bgeo/, diffuse_bgeo/, diffuse_vdb/: the exports (output.*: stage/stage_exports.h)
//   fluid_survey.json         every fluid frame's identity and bounds (io/fluid_survey.h)
//   render_stats.csv          the render's milliseconds per stage, one row per frame drawn
#include <filesystem>
#include <string>

namespace spume {

// "prefix_0012.ext": every per-frame file name spume writes (4 digits, more when needed).
std::string numbered_file_name(const std::string& prefix, int frame, const std::string& extension);

std::filesystem::path fluid_cache_path(const std::filesystem::path& scene_out, int frame);
std::string fluid_cache_pattern(const std::filesystem::path& scene_out);  // for a FluidSource
std::filesystem::path fluid_restart_path(const std::filesystem::path& scene_out, int frame);
std::string fluid_restart_pattern(const std::filesystem::path& scene_out);
std::filesystem::path body_track_path(const std::filesystem::path& scene_out);
std::filesystem::path diffuse_cache_path(const std::filesystem::path& scene_out, int frame);
// The diffuse state of a run's last frame, exact (the caches are quantized): a later run continues from it.
std::filesystem::path diffuse_restart_path(const std::filesystem::path& scene_out, int frame);
std::filesystem::path fluid_survey_path(const std::filesystem::path& scene_out);
std::filesystem::path render_stats_path(const std::filesystem::path& scene_out);

}  // namespace spume
