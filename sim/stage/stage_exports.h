#pragma once
// The exports of a scene's stages (io/frame_export.h), made from their caches:
//   diffuse_bgeo/diffuse_0000.bgeo   output.bgeo: the diffuse frames as classic BGEO (io/bgeo.h)
//   diffuse_vdb/diffuse_0000.vdb     output.vdb: the diffuse frames as OpenVDB points (io/vdb_points_writer.h)
//   fluid_bgeo/fluid_0000.bgeo       output.fluid_bgeo: the solver's fluid frames as classic BGEO
#include <filesystem>
#include <vector>

#include "sim/scene/sim_scene.h"
#include "sim/io/frame_export.h"

namespace spume {

std::vector<FrameExport> diffuse_exports(const SimScene& scene, const std::filesystem::path& scene_out);
std::vector<FrameExport> fluid_exports(const SimScene& scene, const std::filesystem::path& scene_out);

// The frames a stage's folder holds by its record (io/stage_record.h), or `otherwise` without one.
std::vector<int> recorded_frames(const std::filesystem::path& cache_dir, const std::vector<int>& otherwise);

}  // namespace spume
