#pragma once
// The fog volumes export (output.fog, sim/io/fog_volumes.h): the diffuse caches as OpenVDB fog
// volumes, with the radii and absorption the render draws them with, so it lives on the render side
// (the commands keep it in line: render/app/scene/scene_fog.h). Like the other exports
// (sim/io/frame_export.h):
//   diffuse_fog/fog_0000.vdb    one per frame the diffuse caches hold, by their record
// Changing a radius, the absorption or the voxel size writes the files again; no PNG frame depends on it.
#include <filesystem>

#include "render/frame/render_settings.h"
#include "sim/io/frame_export.h"

namespace spume {

// `voxel`: output.fog, m; 0 turns the export off (bring_export_in_line then removes its files).
FrameExport fog_export(const RenderSettings& settings, float voxel, const std::filesystem::path& scene_out);

}  // namespace spume
