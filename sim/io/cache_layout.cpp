#include "sim/io/cache_layout.h"

#include <cstdio>

namespace spume {

std::string numbered_file_name(const std::string& prefix, int frame, const std::string& extension) {
  char digits[16];
  std::snprintf(digits, sizeof digits, "%04d", frame);
  return prefix + "_" + digits + extension;
}

std::filesystem::path fluid_cache_path(const std::filesystem::path& scene_out, int frame) {
  return scene_out / "fluid" / numbered_file_name("fluid", frame, ".spf");
}

std::string fluid_cache_pattern(const std::filesystem::path& scene_out) {
  return (scene_out / "fluid" / "fluid_%04d.spf").string();
}

std::filesystem::path fluid_restart_path(const std::filesystem::path& scene_out, int frame) {
  return scene_out / "fluid" / numbered_file_name("restart", frame, ".spr");
}

std::string fluid_restart_pattern(const std::filesystem::path& scene_out) {
  return (scene_out / "fluid" / "restart_%04d.spr").string();
}

std::filesystem::path body_track_path(const std::filesystem::path& scene_out) { return scene_out / "fluid" / "bodies.csv"; }

std::filesystem::path diffuse_cache_path(const std::filesystem::path& scene_out, int frame) {
  return scene_out / "diffuse" / numbered_file_name("diffuse", frame, ".spd");
}

std::filesystem::path diffuse_restart_path(const std::filesystem::path& scene_out, int frame) {
  return scene_out / "diffuse" / numbered_file_name("restart", frame, ".spd");
}

std::filesystem::path fluid_survey_path(const std::filesystem::path& scene_out) { return scene_out / "fluid_survey.json"; }
std::filesystem::path render_stats_path(const std::filesystem::path& scene_out) { return scene_out / "render_stats.csv"; }

}  // namespace spume
