#pragma once
// What spume makes of a fluid cache before the model sees it: the up axis (fluid.up_axis; "auto" is Z
// for a Blender Mantaflow cache; where the files do not say, measured from a few frames: a free fall
// or a resting layer, io/up_axis_measure.h; else Y), the factor on its stored velocities
// (fluid.velocity_scale; for a Mantaflow cache, unless the key is given, the conversion from its grid
// units to m/s read from its config), its frame rate against a Mantaflow config's, and its stored
// masses against rho0 (2r)^3 (io/stored_mass_check.h). Decided once per sequence, from its first
// frames; the notes say what was decided and why, for the log and `spume info`.
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
  std::optional<double> fps;            // fluid.fps not given: the frame rate a Mantaflow config measures
  std::vector<std::string> notes;
  // A doubt about the stored velocities' units that a measurement settles (Mantaflow's names without
  // its config): said only when the check against the motion does not find them right.
  std::string velocity_units_doubt;
};

struct FluidImportRequest {
  std::vector<std::filesystem::path> files;  // the sequence's files in frame order; the first decides the format
  std::vector<int> frames;                   // their frame numbers (empty: 1, 2, ...)
  std::string up_choice = "auto";            // "auto", "y" or "z"
  std::string vdb_grid;
  std::optional<float> velocity_scale;  // the key's value when the scene gives it
  std::optional<double> fps;            // fluid.fps when the scene gives it (checked against a Mantaflow config's)
  double default_fps = 0.0;             // used where fps is not given and no config measures one (0: Mantaflow's 24)
  float particle_radius = 0.0f;         // > 0: the up axis may be measured and masses are checked
  float rest_density = 0.0f;
};

FluidImport resolve_fluid_import(const FluidImportRequest& request);

// One file, as `spume info` sees it: `up_choice`: "auto", "y" or "z"; `velocity_scale`: the key's value
// when the scene gives it; `fps`: the fluid's frames per second (0: the rate the cache implies). Nothing
// is measured (no radius).
FluidImport resolve_fluid_import(const std::filesystem::path& first_file, const std::string& up_choice,
                                 const std::string& vdb_grid, std::optional<float> velocity_scale, double fps);

}  // namespace spume
