#pragma once
// Blender Mantaflow's per-frame configuration, config/config_####.uni beside data/ (gzip; the fields
// of Blender's FluidDomainSettings written one after another, little-endian: active fields, the
// resolution, dx, dt, the domain's corners p0 p1 in object space, dp0, shift, obj_shift_f, the object
// matrix, base_res, res_min, res_max, active_color, time_total, the cache id), and the units of the
// velocities Mantaflow stores: grid cells per Mantaflow time unit. Blender gives one frame
// frame_length = 0.1 x (25 / fps) x time_scale time units, and time_total grows by it each frame, so
// a stored velocity u is u x cell x frame_length x fps in m/s (x 2.5 x cell at time scale 1).
#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "sim/core/vec.h"

namespace spume {

struct MantaflowConfig {
  std::filesystem::path file;
  std::array<int, 3> resolution{};  // cells along x, y, z (Blender's axes)
  float dx = 0.0f;                  // cell size over the longest side, domain-relative (1 / cells)
  float dt = 0.0f;                  // the last time step, Mantaflow time units
  Vec3f domain_size = Vec3f::Zero();  // m: p1 - p0 through the object matrix
  float cell_size = 0.0f;           // m: the longest side over its cell count
  std::optional<float> time_total;  // Mantaflow time units up to this frame (newer caches only)
  std::string cache_id;             // e.g. "C01"
};

// The config beside a Mantaflow data file: for .../data/fluid_data_0030.vdb, .../config/config_0030.uni,
// if it exists (nullopt otherwise, and for files not named fluid_data_####.vdb).
std::optional<std::filesystem::path> mantaflow_config_path(const std::filesystem::path& data_file);

// Parses a config_####.uni; errors name the file (not gzip, shorter than the fields above, a
// resolution or domain that is not positive).
MantaflowConfig read_mantaflow_config(const std::filesystem::path& file);

struct MantaflowVelocityUnits {
  float factor = 1.0f;  // stored velocity x factor = m/s
  double fps = 0.0;     // the frame rate used
  // The frames per second of simulated time the measured frame length means (Blender: 2.5 Mantaflow
  // time units a second, whatever the bake's time scale); nullopt when no neighbouring config measures it.
  std::optional<double> frame_rate;
  std::string frame_length_how;  // how that frame length was measured, for messages
  std::string how;      // where the factor came from, for the log and `spume info`
};

// The factor for the Mantaflow cache holding `data_file` at `fps` frames per second: the cell size
// from its config, the frame length from the time_total of it and its neighbour config (the time scale
// 1 of Blender's default when no neighbour says more). `fps` 0: the frame rate that frame length means
// at time scale 1 (Blender's, unless its time scale was changed), 24 when not measured. nullopt when
// no config is found.
std::optional<MantaflowVelocityUnits> mantaflow_velocity_units(const std::filesystem::path& data_file, double fps);

}  // namespace spume
