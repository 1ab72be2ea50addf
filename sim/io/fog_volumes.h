#pragma once
// Diffuse frames as fog volumes (.vdb) for other renderers' volume shaders. Each drawn type's particles
// are the spheres spume's renderer draws (radius r_t), and the file holds, on one voxel lattice:
//   spray, foam, bubble   FloatGrid: the fraction of each voxel inside that type's spheres
//   density               FloatGrid: their sum
//   v                     Vec3SGrid: the material's velocity, m/s (the volume-weighted mean)
// Each sphere's volume 4/3 pi r_t^3 is spread over voxels with weights that sum to one, so a grid's
// integral (sum x voxel^3) is its particles' volume; where spheres overlap their fractions add. With
// the file's "alpha" (render.alpha) as the extinction coefficient, alpha x density gives the optical
// depth Eq. 9 gives the spheres where they do not overlap. Spheres no larger than a voxel are spread
// over the 8 voxels around their centre (trilinear: centroid kept); larger ones over the voxels they
// cover, each weighted by how far inside the sphere its centre lies (a one-voxel ramp at the rim).
// Deterministic: the bytes depend only on the frame and the look, never on the thread count.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/core/frames.h"

namespace spume {

struct FogLook {
  float voxel = 0.0f;                                // m
  std::array<float, kDiffuseTypeCount> radius{};     // m, per type; 0: the type is not drawn, no grid
  float alpha = 0.0f;                                // 1/m, render.alpha: stored as metadata
};

// One voxel's share of a sphere: index-space coordinates (voxel centres at integers) and weight.
struct VoxelWeight {
  std::array<int, 3> ijk;
  double weight;
};
// The voxels a sphere at `centre` (m) of `radius` spreads over, weights summing to one.
std::vector<VoxelWeight> sphere_voxel_weights(const Vec3f& centre, float radius, float voxel);
void sphere_voxel_weights(const Vec3f& centre, float radius, float voxel, std::vector<VoxelWeight>& out);

// What fixes the bytes besides the frame, for records.
std::string fog_volumes_format(const FogLook& look);

std::string fog_volume_bytes(const DiffuseFrame& frame, const FogLook& look);
// Written atomically. Throws Error naming the path when the look is unusable or writing fails.
void write_fog_volumes(const std::filesystem::path& path, const DiffuseFrame& frame, const FogLook& look);

}  // namespace spume
