#pragma once
// The OpenVDB side of spume's .vdb reading and writing, built into the module libspume_vdb.so
// (io/vdb_module.h). Each function does what the function of the same purpose in vdb_points.h,
// vdb_points_writer.h or fog_volumes.h documents; those reach these through the module's table.
#include <filesystem>
#include <span>
#include <string>

#include "sim/core/frames.h"
#include "sim/io/fog_volumes.h"
#include "sim/io/vdb_points.h"

namespace spume::openvdb_io {

VdbContents read_contents(const std::filesystem::path& path, const std::string& grid, VdbPointsInfo* info);
FluidFrame read_points(const std::filesystem::path& path, const std::string& grid, VdbPointsInfo* info);
std::string points_bytes(const DiffuseFrame& frame, float voxel_size, std::span<const float> ages);
std::string fog_bytes(const DiffuseFrame& frame, const FogLook& look);

}  // namespace spume::openvdb_io
