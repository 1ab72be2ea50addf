#pragma once
// What spume makes of a fluid cache before the model sees it: the up axis (fluid.up_axis; "auto" is Z
// for a Blender Mantaflow cache, Y otherwise) and the factor on its stored velocities
// (fluid.velocity_scale; for a Mantaflow cache, unless the key is given, the conversion from its grid
// units to m/s read from its config). Decided once per sequence, from its first file; the notes say
// what was decided and why, for the log and `spume info`.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/io/fluid_read_options.h"

namespace spume {

struct FluidImport {
  FluidReadOptions read;
  float velocity_scale = 1.0f;
  bool velocity_scale_derived = false;  // from a Mantaflow config, not from the key
  bool mantaflow = false;               // a Blender Mantaflow cache: FLIP particles (fluid.particles "auto")
  std::vector<std::string> notes;
};

// `up_choice`: "auto", "y" or "z"; `velocity_scale`: the key's value when the scene gives it;
// `fps`: the fluid's frames per second (0 in `spume info`: the rate the cache implies).
FluidImport resolve_fluid_import(const std::filesystem::path& first_file, const std::string& up_choice,
                                 const std::string& vdb_grid, std::optional<float> velocity_scale, double fps);

}  // namespace spume
