#include "sim/io/fluid_import.h"

#include "sim/core/error.h"
#include "sim/io/mantaflow_config.h"

namespace spume {

FluidImport resolve_fluid_import(const std::filesystem::path& first_file, const std::string& up_choice,
                                 const std::string& vdb_grid, std::optional<float> velocity_scale, double fps) {
  FluidImport in;
  in.read.vdb_grid = vdb_grid;
  const std::optional<std::filesystem::path> config = mantaflow_config_path(first_file);
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
  }
  return in;
}

}  // namespace spume
