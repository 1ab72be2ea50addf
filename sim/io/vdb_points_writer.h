#pragma once
// Diffuse frames as OpenVDB points (.vdb), for Houdini and other OpenVDB tools. One PointDataGrid
// named "points", Blosc-compressed, with these point attributes:
//   P         position: 16-bit fixed point within its voxel (OpenVDB's FixedPointCodec<false>),
//             rounded to the nearest step, so each axis is off by at most vdb_position_error(voxel)
//   v         velocity, m/s: half floats (TruncateCodec), off by at most vdb_velocity_error(|v|)
//   lifetime  float, s remaining: exact
//   id        int64: exact, the bits of the unsigned id (parent fluid id, birth step, sample; frames.h),
//             so ids whose parent is 2^31 or more show as negative in tools that read it as signed
//   type      int32: 0 spray, 1 foam, 2 bubble; and point groups "spray", "foam", "bubble"
// The file's bytes depend only on the frame and the voxel size: OpenVDB stamps every file with a random
// UUID, which is replaced by one derived from the rest of the file (same content, same UUID).
// OpenVDB itself is opened only by runs that write or read .vdb files (io/vdb_module.h).
#include <filesystem>
#include <span>
#include <string>

#include "sim/core/frames.h"

namespace spume {

// Fixed-point steps across one voxel in a position (16 bits per axis).
inline constexpr double kVdbPositionSteps = 65535.0;

// The voxel spume writes diffuse points with: the fluid's particle spacing 2 r.
float vdb_points_voxel_size(float particle_radius);
// Largest error of a position coordinate (m): half a fixed-point step, voxel / 131070 (with 4% for the
// codec's float arithmetic), plus half a float ulp of the coordinate for a reader that stores it as a
// float (OpenVDB's own conversion computes world positions in double).
double vdb_position_error(float voxel_size, float coordinate);
// Largest error of a velocity component stored as a half float: 2^-11 relative (round to nearest;
// 11 significant bits), 2^-25 m/s absolute below half's normal range (6.1e-5).
double vdb_velocity_error(float component);

// What fixes the bytes besides the frame, for records: "spume-vdb-points 1, OpenVDB 10.0.1, voxel V".
std::string vdb_points_format(float voxel_size);

// The whole .vdb file as bytes (deterministic: the same for any thread count). With `ages` (one per
// particle, s: io/diffuse_age.h), also `age` and `life` = age + the remaining lifetime, Houdini's names.
std::string vdb_points_bytes(const DiffuseFrame& frame, float voxel_size, std::span<const float> ages = {});
// Written atomically (core/atomic_file.h). Throws Error naming the path on failure; a component
// beyond half's range (65504 m/s) is an error rather than an infinity.
void write_vdb_points(const std::filesystem::path& path, const DiffuseFrame& frame, float voxel_size,
                      std::span<const float> ages = {});

}  // namespace spume
