#pragma once
// The simulation half of a scene file, validated into plain values. The render half is read by
// render/; whoever loads the file calls ParamReader::reject_unknown_keys() after both.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "sim/core/frames.h"
#include "sim/core/params.h"
#include "sim/io/fluid_read_options.h"
#include "sim/diffuse/params.h"
#include "sim/scene/fluid_scene_reader.h"
#include "sim/geometry/solids.h"

namespace spume {

enum class FluidSourceKind { Files, Solver };

// Whether a tank is inferred from the fluid files (scene/container.h): never; only when the fluid was
// seen stopped at a floor and all four sides (the one-line --fluid run without --tank: otherwise it
// runs with no tank and the log says why); or as the scene asks ({"infer": true}: no floor found is
// an error, open sides lie far away).
enum class TankInference { Off, IfEvident, Required };

struct SimScene {
  std::string name;                     // output folder name: OUT/<name>/
  FluidSourceKind source = FluidSourceKind::Files;
  std::string file_pattern;             // Files: resolved against the scene file's folder
  bool allow_gaps = false;              // Files: frames missing between files are interpolated
  float velocity_scale = 1.0f;          // Files: factor on the stored velocities (caches in other units)
  bool flip_particles = false;          // fluid.particles = flip (MODEL.md §9.2)
  bool fill_narrow_band = true;         // fluid.narrow_band = auto (MODEL.md §9.1)
  FluidReadOptions read;                // Files: the up axis, the VDB grid (io/fluid_import.h)
  std::vector<std::string> import_notes;  // what was decided about the name and (files) the axis and units, and why
  std::string velocity_units_doubt;     // Files: said unless the velocity check finds them right (io/fluid_import.h)
  FluidSequenceInfo fluid;
  std::optional<std::pair<int, int>> frames;  // inclusive frame range to use, if limited
  Vec3f gravity = Vec3f(0.0f, -9.81f, 0.0f);  // m/s^2
  SolidSet solids;
  TankInference infer_container = TankInference::Off;  // Files: a tank found from the fluid
  Aabb domain;                          // empty: derived from the tank or every fluid frame's bounds
  DiffuseParams diffuse;
  bool write_bgeo = false;              // also write diffuse frames as BGEO for Houdini/Blender
  bool write_fluid_bgeo = false;        // Solver: also write the fluid frames as BGEO
  bool write_vdb = false;               // also write diffuse frames as OpenVDB points (stage/stage_exports.h)
  float fog_voxel = 0.0f;               // m; > 0: render writes fog volumes of the diffuse frames (io/fog_volumes.h)

  // Solver: the solver's settings and initial fluid. It simulates frames 0..frames->second (always
  // set for solver scenes: fluid.frames, declared in keys/scene_keys.h).
  FluidSolverSetup solver;

  // Every key that shapes the fluid frames (gravity, fluid, solids; not the frame range) and, with
  // the diffuse keys, domain and output added, the diffuse frames, as JSON at the values used
  // (defaults included: ParamReader::effective; objects compare equal whatever the key order). Cache
  // folders record them (io/stage_record.h); a difference of value means stale.
  Json fluid_keys;
  Json diffuse_keys;
};


// `scene_dir` resolves relative file paths; `default_name` is used when the scene has no "name".
SimScene read_sim_scene(const ParamReader& root, const std::filesystem::path& scene_dir,
                        const std::string& default_name);

// A tank and, over an open top, the air above it to the tank's height again: where the water and
// its spray are (without the ground beside it).
Aabb tank_with_air_above(const Solid& tank);

// The domain used when the scene gives none: the tanks if there are any, each as tank_with_air_above
// and an open one widened on each side by its height (spray thrown over its rim falls beside it to
// its floor), else the fluid's bounds over the whole sequence grown by their extent on every side (at
// least 8 h), so nothing the flow reaches is lost and spray falling away is.
Aabb default_domain(const SimScene& scene, const Aabb& fluid_bounds);

}  // namespace spume
