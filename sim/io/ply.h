#pragma once
// PLY point clouds (ascii, binary_little_endian, binary_big_endian).
// Reads element `vertex`: x, y, z (any numeric type) required; velocity from vx, vy, vz or
// velocity_x, velocity_y, velocity_z; ids from an integral `id` (0 .. 2^32-1); masses from `mass`.
// Other properties, list properties and other elements (faces, ...) are skipped.
#include <filesystem>
#include <vector>

#include "sim/core/frames.h"
#include "sim/io/point_attribute.h"

namespace spume {

// *attributes receives the vertex properties (x, y, z included).
FluidFrame read_ply(const std::filesystem::path& path, std::vector<PointAttribute>* attributes = nullptr);

// binary_little_endian: float x y z, then float vx vy vz, uint id, float mass when the frame has them.
void write_ply(const std::filesystem::path& path, const FluidFrame& frame);

}  // namespace spume
