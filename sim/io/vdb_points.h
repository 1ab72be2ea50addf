#pragma once
// OpenVDB point caches (.vdb): Blender Mantaflow's fluid_data_####.vdb, Houdini's VDB points, any
// file with point data grids. Positions go through each grid's transform (world space); velocity, id
// (int32 or int64) and mass (float) under the names of io/attribute_names.h, any codec. OpenVDB is
// opened only by runs that read or write .vdb files (io/vdb_module.h): this header is what the rest
// of spume sees.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/core/frames.h"

namespace spume {

struct VdbGridInfo {
  std::string name;
  std::string type;          // OpenVDB's grid type, e.g. "ptdataidx32_ptdata", "Tree_vec3s_5_4_3"
  double voxel_size = 0.0;   // m (the transform's voxel size along x)
  bool points = false;       // a point data grid
  uint64_t count = 0;        // points (point grids) or active voxels (other grids)
  bool used = false;         // spume reads its points
};

struct VdbAttributeInfo {
  std::string grid, name, type, codec;  // e.g. "particles", "P", "vec3s", "trnc"
};

struct VdbPointsInfo {
  std::vector<VdbGridInfo> grids;
  std::vector<VdbAttributeInfo> attributes;  // of every point grid, in the grids' order
  std::string velocity_attribute;            // "" without velocities
  std::string id_attribute;                  // "" without ids
  std::string mass_attribute;                // "" without masses
  std::string choice;                        // which point grids were read, and why
};

// Reads the points of the point data grid named `grid` ("" for every point data grid in the file,
// in the file's order). Errors name the file: not a VDB, cut or damaged, no point data grid, no grid
// of that name, an attribute of a type spume cannot read as velocity or id, spume's own diffuse export
// (read_vdb_contents reads it). Grids that disagree on having velocities or ids are refused (the frame
// would mix).
FluidFrame read_vdb_points(const std::filesystem::path& path, const std::string& grid = "",
                           VdbPointsInfo* info = nullptr);

// A grid of values rather than points (a fog volume, a level set, a velocity field), as read in full.
struct VdbVolumeInfo {
  std::string name, grid_class;  // class as OpenVDB names it: "fog volume", "level set", "unknown"
  uint64_t active_voxels = 0;
  bool scalar = false;                 // a float grid: the figures below are set
  double min = 0.0, max = 0.0;         // of its active values
  double integral = 0.0;               // sum of its active values x voxel volume (m^3 for volume fractions)
};

// What a .vdb holds: fluid points, or spume's own diffuse export (io/vdb_points_writer.h: every point
// grid read has `lifetime` (float), `type` (int32), `id` and a velocity; its ids are 64-bit).
struct VdbContents {
  FluidFrame fluid;                     // the points, when they are not spume's diffuse export
  std::optional<DiffuseFrame> diffuse;  // spume's diffuse export, with its frame and time metadata
  std::vector<float> diffuse_ages;      // its particles' `age` (s), when every grid read carries it
  std::vector<VdbVolumeInfo> volumes;   // a file of volumes and no points (e.g. spume's fog export): its grids
  int frame_index = 0;                  // the grid's "frame" and "time" metadata, when it has them
  double time = 0.0;
};
// The same reading and errors as read_vdb_points, but spume's diffuse export is read as such, and a
// file of volumes only is described (`volumes`) instead of refused.
VdbContents read_vdb_contents(const std::filesystem::path& path, const std::string& grid = "",
                              VdbPointsInfo* info = nullptr);

// True when the file starts with OpenVDB's magic number.
bool has_vdb_magic(const std::filesystem::path& path);

}  // namespace spume
