#include "sim/io/fluid_import.h"

#include <cmath>

#include "sim/core/error.h"
#include "sim/io/io_bytes.h"
#include "sim/io/mantaflow_config.h"
#include "sim/io/particle_file.h"
#include "sim/io/stored_mass_check.h"
#include "sim/io/up_axis_measure.h"
#include "sim/io/vdb_points.h"

namespace spume {
namespace {

// A frame rate within 1% of a Mantaflow config's is that rate (its frame length is a float).
constexpr double kFrameRateTolerance = 0.01;
constexpr size_t kMeasuredFrames = 3;  // the first three (a fall), and the last (a layer)

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

// Houdini's formats (Y-up by Houdini's convention) and spume's own caches say their axis.
// A name of no known format says nothing either; reading it later says what is wrong.
bool format_says_up(const std::filesystem::path& file) {
  try {
    const ParticleFormat f = particle_format(file);
    return f == ParticleFormat::Bgeo || f == ParticleFormat::HoudiniGeometry || f == ParticleFormat::FluidCache;
  } catch (const Error&) {
    return true;
  }
}

// The frames the import measures, as stored: the first kMeasuredFrames and the last.
struct Sampled {
  std::vector<FluidFrame> frames;
  std::vector<int> numbers;
};

Sampled read_sampled(const FluidImportRequest& r) {
  Sampled s;
  FluidReadOptions as_stored;
  as_stored.vdb_grid = r.vdb_grid;
  for (size_t k = 0; k < r.files.size(); ++k) {
    if (k >= kMeasuredFrames && k + 1 != r.files.size()) continue;
    s.frames.push_back(read_fluid_file(r.files[k], as_stored));
    s.numbers.push_back(r.frames.size() == r.files.size() ? r.frames[k] : int(k) + 1);
  }
  return s;
}

void check_frame_rate(const FluidImportRequest& r, const MantaflowVelocityUnits& units, FluidImport& in) {
  if (!units.frame_rate) return;
  const double rate = *units.frame_rate;
  if (!r.fps) {
    in.fps = rate;
    in.notes.push_back(str("fluid.fps: ", rate, " (not given: the Mantaflow config's ", units.frame_length_how,
                           " at 2.5 time units a second); fluid.fps sets it"));
    return;
  }
  if (std::fabs(*r.fps / rate - 1.0) <= kFrameRateTolerance) return;
  const std::string said = str("fluid.fps = ", *r.fps, " (--fps), but the Mantaflow config's ", units.frame_length_how,
                               " is ", rate, " frames per second of simulated time (Blender: 2.5 time units a second, "
                               "whatever the bake's time scale)");
  if (in.velocity_scale_derived)
    fail(said, ": the velocities' conversion to m/s and every frame interval would be ", *r.fps / rate,
         " times off. Set fluid.fps (--fps) to ", rate, " (or give fluid.velocity_scale to convert the velocities "
         "yourself)");
  in.notes.push_back(str("warning: ", said, ": frame intervals are ", *r.fps / rate, " times too short for the motion "
                         "the bake simulated; set fluid.fps (--fps) to ", rate));
}

// "auto" where neither a config nor the format says: measured, else Mantaflow's names, else y.
void decide_measured_axis(const FluidImportRequest& r, bool mantaflow_names, const Sampled& sampled, FluidImport& in) {
  const double fps = r.fps ? *r.fps : r.default_fps > 0.0 ? r.default_fps : 24.0;
  const UpAxisMeasure m = measure_up_axis(sampled.frames, sampled.numbers, fps, r.particle_radius);
  const std::string names = mantaflow_names ? "Mantaflow's names ('particles' with 'particles_velocity') but no config/"
                                            : "nothing in the files says which way is up";
  if (m.axis == 1 || m.axis == 2) {
    in.read.up = m.axis == 2 ? UpAxis::Z : UpAxis::Y;
    in.notes.push_back(str("up axis: ", m.axis == 2 ? "z" : "y", " (fluid.up_axis \"auto\": ", names, "; measured: ",
                           m.how, ")", m.axis == 2 ? "; the cache's (x, y, z) is read as spume's (x, z, -y)" : "",
                           "; fluid.up_axis = \"", m.axis == 2 ? "y" : "z", "\" reads it the other way"));
    if (m.sign < 0)
      in.notes.push_back(str("warning: the fluid falls toward +", m.axis == 2 ? "z" : "y",
                             ", so it is upside down for either choice of fluid.up_axis; spume's gravity pulls "
                             "toward -y"));
    return;
  }
  in.read.up = mantaflow_names ? UpAxis::Z : UpAxis::Y;
  if (m.axis == 0) {
    in.notes.push_back(str("warning: up axis: the fluid's gravity is along x (measured: ", m.how, "), which "
                           "fluid.up_axis (y or z) cannot turn; read ", mantaflow_names ? "Z" : "Y", "-up, so gravity "
                           "(spume's -y) pulls sideways"));
    return;
  }
  in.notes.push_back(mantaflow_names
                         ? str("up axis: z (fluid.up_axis \"auto\": a point grid 'particles' with 'particles_velocity' "
                               "is Blender Mantaflow's, and Blender is Z-up; measured nothing: ", m.how,
                               "); the cache's (x, y, z) is read as spume's (x, z, -y); fluid.up_axis = \"y\" keeps it "
                               "as it is")
                         : str("up axis: y (fluid.up_axis \"auto\": ", names, ", and ", m.how,
                               "); fluid.up_axis = \"z\" turns a Z-up cache"));
}

}  // namespace

FluidImport resolve_fluid_import(const FluidImportRequest& r) {
  if (r.files.empty()) fail("resolve_fluid_import: no files");
  const std::filesystem::path& first_file = r.files.front();
  FluidImport in;
  in.read.vdb_grid = r.vdb_grid;
  const std::optional<std::filesystem::path> config = mantaflow_config_path(first_file);
  const std::optional<double> voxel = config ? std::nullopt : mantaflow_voxel_size(first_file);
  in.mantaflow = config || voxel;
  // The frames measured: only when a radius is given (a scene), and then the first is read once.
  const bool measure_axis = r.up_choice == "auto" && !config && r.particle_radius > 0.0f && !format_says_up(first_file);
  const bool check_masses = r.particle_radius > 0.0f && r.rest_density > 0.0f;
  Sampled sampled;
  try {
    if (measure_axis) {
      sampled = read_sampled(r);
    } else if (check_masses) {
      FluidReadOptions as_stored;
      as_stored.vdb_grid = r.vdb_grid;
      sampled.frames.push_back(read_fluid_file(first_file, as_stored));
    }
  } catch (const Error&) {
    sampled = Sampled{};  // a file that cannot be read: the survey names it, with its frame
  }

  if (r.up_choice == "z") {
    in.read.up = UpAxis::Z;
    in.notes.push_back("up axis: z (fluid.up_axis = \"z\"): the cache's (x, y, z) is read as spume's (x, z, -y)");
  } else if (r.up_choice == "y") {
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
  } else if (measure_axis && !sampled.frames.empty()) {
    decide_measured_axis(r, voxel.has_value(), sampled, in);
  } else if (voxel) {
    in.read.up = UpAxis::Z;
    in.notes.push_back("up axis: z (fluid.up_axis \"auto\": a point grid 'particles' with 'particles_velocity' is "
                       "Blender Mantaflow's, and Blender is Z-up); the cache's (x, y, z) is read as spume's (x, z, -y); "
                       "fluid.up_axis = \"y\" keeps it as it is");
  }

  if (check_masses && !sampled.frames.empty()) {
    const StoredMassCheck masses =
        check_stored_masses(sampled.frames.front(), first_file.string(), r.particle_radius, r.rest_density);
    in.read.stored_masses = masses.use_stored;
    if (!masses.note.empty()) in.notes.push_back(masses.note);
  }

  if (r.velocity_scale) {
    in.velocity_scale = *r.velocity_scale;
    if (config) {
      in.notes.push_back(str("velocities: fluid.velocity_scale = ", *r.velocity_scale,
                             " as given (the Mantaflow config beside the cache is not used for their units)"));
      if (const auto units = mantaflow_velocity_units(first_file, r.fps.value_or(0.0))) check_frame_rate(r, *units, in);
    }
    return in;
  }
  if (config) {
    const auto units = mantaflow_velocity_units(first_file, r.fps.value_or(0.0));
    in.velocity_scale = units->factor;
    in.velocity_scale_derived = true;
    in.notes.push_back(str("velocities: x ", units->factor, " to m/s (", units->how,
                           "); fluid.velocity_scale overrides it"));
    check_frame_rate(r, *units, in);
  } else if (voxel && in.read.up == UpAxis::Z) {
    // Without the config the frame length is unknown: Blender's at time scale 1 is the likely one.
    in.velocity_units_doubt =
        str("warning: ", first_file.string(), " is a Blender Mantaflow cache (a point grid 'particles' with "
            "'particles_velocity'), whose velocities are in grid cells per Mantaflow time unit, but no config/",
            "config_####.uni lies beside its data/ folder to convert them: they are used as they are, about 1 / (2.5 x "
            "cell) times too fast. Put the bake's config/ folder beside data/, or set fluid.velocity_scale = 2.5 x "
            "cell = ", 2.5 * *voxel, " (the cell is the grid's voxel size, ", *voxel, " m; 2.5 assumes Blender's time "
            "scale 1)");
  }
  return in;
}

FluidImport resolve_fluid_import(const std::filesystem::path& first_file, const std::string& up_choice,
                                 const std::string& vdb_grid, std::optional<float> velocity_scale, double fps) {
  FluidImportRequest r;
  r.files = {first_file};
  r.up_choice = up_choice;
  r.vdb_grid = vdb_grid;
  r.velocity_scale = velocity_scale;
  if (fps > 0.0) r.fps = fps;
  FluidImport in = resolve_fluid_import(r);
  // Without a run's velocity check to settle it, the doubt is said as it is.
  if (!in.velocity_units_doubt.empty()) in.notes.push_back(in.velocity_units_doubt);
  return in;
}

}  // namespace spume
