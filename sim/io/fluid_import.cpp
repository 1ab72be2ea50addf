#include "sim/io/fluid_import.h"

#include "sim/core/error.h"
#include "sim/io/io_bytes.h"
#include "sim/io/mantaflow_config.h"
#include "sim/io/vdb_points.h"

namespace spume {
namespace {

// Mantaflow's own names in a .vdb (a point grid 'particles' with 'particles_velocity'): its voxel size,
// which Mantaflow makes its cell size. For a cache whose config/ was left behind.
std::optional<double> mantaflow_voxel_size(const std::filesystem::path& file) {
  if (!io::ends_with(io::lower_file_name(file), ".vdb") || !has_vdb_magic(file)) return std::nullopt;
  VdbPointsInfo info;
  try {
    read_vdb_points(file, "particles", &info);
  } catch (const Error&) {
    return std::nullopt;  // not Mantaflow's layout; reading the frame later says what is wrong
  }
  if (info.velocity_attribute != "particles_velocity") return std::nullopt;
  for (const VdbGridInfo& g : info.grids)
    if (g.used) return g.voxel_size;
  return std::nullopt;
}

}  // namespace

FluidImport resolve_fluid_import(const std::filesystem::path& first_file, const std::string& up_choice,
                                 const std::string& vdb_grid, std::optional<float> velocity_scale, double fps) {
  FluidImport in;
  in.read.vdb_grid = vdb_grid;
  const std::optional<std::filesystem::path> config = mantaflow_config_path(first_file);
  const std::optional<double> voxel = config ? std::nullopt : mantaflow_voxel_size(first_file);
  in.mantaflow = config || voxel;
  if (up_choice == "z") {
    in.read.up = UpAxis::Z;
    in.notes.push_back("up axis: z (fluid.up_axis = \"z\"): the cache's (x, y, z) is read as spume's (x, z, -y)");
  } else if (up_choice == "y") {
    in.read.up = UpAxis::Y;
    if (config)
      in.notes.push_back(str("up axis: y (fluid.up_axis = \"y\"), although ", config->string(),
                             " makes this a Blender Mantaflow cache, which is Z-up: gravity (-y) will pull "
                             "sideways; \"auto\" or \"z\" turns it"));
  } else if (config) {
    in.read.up = UpAxis::Z;
    in.notes.push_back(str("up axis: z (fluid.up_axis \"auto\": ", config->filename().string(),
                           " beside the data makes this a Blender Mantaflow cache, and Blender is Z-up); the cache's "
                           "(x, y, z) is read as spume's (x, z, -y); fluid.up_axis = \"y\" keeps it as it is"));
  } else if (voxel) {
    in.read.up = UpAxis::Z;
    in.notes.push_back("up axis: z (fluid.up_axis \"auto\": a point grid 'particles' with 'particles_velocity' is "
                       "Blender Mantaflow's, and Blender is Z-up); the cache's (x, y, z) is read as spume's (x, z, -y); "
                       "fluid.up_axis = \"y\" keeps it as it is");
  }
  if (velocity_scale) {
    in.velocity_scale = *velocity_scale;
    if (config)
      in.notes.push_back(str("velocities: fluid.velocity_scale = ", *velocity_scale,
                             " as given (the Mantaflow config beside the cache is not used for their units)"));
    return in;
  }
  if (config) {
    const auto units = mantaflow_velocity_units(first_file, fps);
    in.velocity_scale = units->factor;
    in.velocity_scale_derived = true;
    in.notes.push_back(str("velocities: x ", units->factor, " to m/s (", units->how,
                           "); fluid.velocity_scale overrides it"));
  } else if (voxel) {
    // Without the config the frame length is unknown: Blender's at time scale 1 is the likely one.
    in.notes.push_back(str("warning: ", first_file.string(), " is a Blender Mantaflow cache (a point grid 'particles' "
                           "with 'particles_velocity'), whose velocities are in grid cells per Mantaflow time unit, "
                           "but no config/", "config_####.uni lies beside its data/ folder to convert them: they are "
                           "used as they are, about 1 / (2.5 x cell) times too fast. Put the bake's config/ folder "
                           "beside data/, or set fluid.velocity_scale = 2.5 x cell = ", 2.5 * *voxel,
                           " (the cell is the grid's voxel size, ", *voxel, " m; 2.5 assumes Blender's time scale 1)"));
  }
  return in;
}

}  // namespace spume
