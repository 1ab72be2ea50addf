#include "sim/scene/sim_scene.h"

#include "sim/core/error.h"
#include "sim/io/fluid_import.h"
#include "sim/io/frame_pattern.h"
#include "sim/io/io_bytes.h"
#include "sim/scene/diffuse_params_reader.h"
#include "sim/scene/scene_name.h"
#include "sim/keys/scene_keys.h"
#include "sim/scene/solids_reader.h"

namespace spume {
namespace {

// Bump when a change of spume's code makes old caches wrong.
// 2: walls count only where wet, emission along the motion, the whole sequence's domain.
constexpr int kFluidCacheGeneration = 2;
// 3: a tank's domain reaches beside it, where spray thrown over the rim falls; newborns sampled into
// a wall stay on their fluid particle's side.
constexpr int kDiffuseCacheGeneration = 3;
// Solver scenes with dynamic bodies only, so that the others keep their fluid caches.
// 2: the bodies keep a skin of 2r from the solids (fluid/rigid_bodies.h). 3: Bullet starts every
// frame afresh from the bodies' poses, so that a run continues from its restart state.
constexpr int kBodiesGeneration = 3;

Json with_generation(Json keys, int generation) {
  keys["spume_cache_generation"] = generation;
  return keys;
}

// The scene's name: the key's, which must be usable as it is, or the one derived from the scene
// file's (or the fluid files') name, made usable and said so in `notes`.
std::string read_scene_name(const ParamReader& root, const std::string& default_name, std::vector<std::string>& notes) {
  const std::string given = root.text(keys::scene::name.name(), default_name);
  if (is_usable_scene_name(given)) return given;
  const std::string usable = usable_scene_name(given);
  const std::string allowed = "is not a usable folder name (letters, digits, _ - . only)";
  if (root.has(keys::scene::name.name()))
    root.fail_at("name", str("\"", given, "\" ", allowed, usable.empty() ? "" : str("; e.g. \"", usable, "\"")));
  if (usable.empty())
    root.fail_at("name", str("\"", given, "\", taken from the file name, ", allowed,
                             "; give the scene a name with the key name (or --set name=NAME)"));
  notes.push_back(str("scene name: ", usable, ", the folder of its results (taken from the file name \"", given,
                      "\", which ", allowed, "); the key name (or --set name=NAME) gives another"));
  return usable;
}

// fluid.vdb_grid means something only to OpenVDB files.
bool reads_vdb_grids(const std::string& file_pattern) {
  return io::ends_with(io::lower_file_name(std::filesystem::path(file_pattern)), ".vdb");
}

// The axis, the units, the frame rate and the masses are decided from the first frames (a Mantaflow
// config beside them, or what they show), within fluid.frames when it is given.
FluidImportRequest import_request(const ParamReader& fluid, const SimScene& scene) {
  namespace k = keys;
  FluidImportRequest request;
  if (fluid.has(k::fluid::velocity_scale.name())) request.velocity_scale = scene.velocity_scale;
  if (fluid.has(k::fluid::fps.name())) request.fps = scene.fluid.fps;
  request.default_fps = scene.fluid.fps;
  request.up_choice = fluid.choice(k::fluid::up_axis);
  request.vdb_grid = fluid.text(k::fluid::vdb_grid.name(), "");
  request.particle_radius = scene.fluid.particle_radius;
  request.rest_density = scene.fluid.rest_density;
  if (is_frame_pattern(scene.file_pattern)) {
    std::optional<std::pair<double, double>> range;
    if (fluid.has(k::fluid::frames.name())) range = fluid.range(k::fluid::frames);
    for (const int f : find_pattern_frames(scene.file_pattern))
      if (!range || (f >= range->first && f <= range->second))
        request.files.push_back(expand_frame_pattern(scene.file_pattern, f)), request.frames.push_back(f);
  }
  if (request.files.empty()) {  // nothing to measure: the survey says what is missing
    request.files = {scene.file_pattern}, request.frames.clear();
    request.particle_radius = 0.0f;
  }
  return request;
}

}  // namespace

SimScene read_sim_scene(const ParamReader& root, const std::filesystem::path& scene_dir,
                        const std::string& default_name) {
  namespace k = keys;
  SimScene scene;
  scene.name = read_scene_name(root, default_name, scene.import_notes);
  scene.gravity = root.vec3(k::scene::gravity);

  const ParamReader fluid = root.child("fluid");
  scene.source = fluid.choice(k::fluid::source) == "files" ? FluidSourceKind::Files : FluidSourceKind::Solver;
  scene.fluid.particle_radius = float(fluid.number(k::fluid::radius));
  const double r = scene.fluid.particle_radius;
  scene.fluid.support_radius = float(fluid.number(k::fluid::support_radius, r));
  if (scene.fluid.support_radius < scene.fluid.particle_radius)
    fluid.fail_at("support_radius", str("value ", scene.fluid.support_radius, " is below the particle radius ",
                                        scene.fluid.particle_radius, "; the usual choice is 4 x radius"));
  scene.fluid.fps = fluid.number(k::fluid::fps);
  scene.fluid.rest_density = float(fluid.number(k::fluid::rest_density));
  const std::string particles = fluid.choice(k::fluid::particles);
  scene.flip_particles = particles == "flip";
  scene.fill_narrow_band = fluid.choice(k::fluid::narrow_band) == "auto";
  if (scene.source == FluidSourceKind::Files) {
    const auto files = fluid.optional_text(k::fluid::files.name());
    if (!files) fluid.fail_at("files", "missing: a file pattern such as \"cache/ParticleData_Fluid_%d.bgeo\"");
    const std::filesystem::path pattern(*files);
    scene.file_pattern = pattern.is_absolute() ? pattern.string() : (scene_dir / pattern).lexically_normal().string();
    scene.allow_gaps = fluid.boolean(k::fluid::allow_gaps);
    scene.velocity_scale = float(fluid.number(k::fluid::velocity_scale));
    const FluidImport import = resolve_fluid_import(import_request(fluid, scene));
    if (import.fps) scene.fluid.fps = *import.fps;
    scene.velocity_units_doubt = import.velocity_units_doubt;
    scene.read = import.read;
    if (!reads_vdb_grids(scene.file_pattern)) {
      if (fluid.has(k::fluid::vdb_grid.name()))
        scene.import_notes.push_back(str("warning: fluid.vdb_grid \"", scene.read.vdb_grid, "\" does not apply to ",
                                         std::filesystem::path(scene.file_pattern).filename().string(),
                                         " (it picks a point grid of an OpenVDB .vdb cache): ignored"));
      scene.read.vdb_grid.clear();
    }
    scene.velocity_scale = import.velocity_scale;
    scene.import_notes.insert(scene.import_notes.end(), import.notes.begin(), import.notes.end());
    if (particles == "auto" && import.mantaflow) {
      scene.flip_particles = true;
      scene.import_notes.push_back("particles: flip (fluid.particles \"auto\": Mantaflow's particles are FLIP "
                                   "particles, so the potentials use velocities averaged over 2 h and the counts the "
                                   "frame's own particle density, MODEL.md §9.2); fluid.particles = \"sph\" takes them "
                                   "as SPH particles");
    }
  }
  if (scene.source == FluidSourceKind::Solver) scene.solver = read_fluid_solver(fluid, scene.gravity);
  // Files: every file found unless limited; the solver: the declared range unless given.
  if (scene.source == FluidSourceKind::Solver || fluid.has(k::fluid::frames.name())) {
    const auto [a, b] = fluid.range(k::fluid::frames);
    if (a != std::floor(a) || b != std::floor(b)) fluid.fail_at("frames", "expected [first, last] whole frame numbers");
    scene.frames = std::make_pair(int(a), int(b));
  }

  if (root.has("domain")) {
    const ParamReader domain = root.child("domain");
    scene.domain.min = domain.vec3(k::domain::min);
    scene.domain.max = domain.vec3(k::domain::max);
    if (!(scene.domain.min.array() < scene.domain.max.array()).all())
      root.fail_at("domain", "min must be below max on every axis");
  }

  bool infer_tank = false;
  scene.solids = scene.source == FluidSourceKind::Files ? read_solids(root, scene.gravity, infer_tank)
                                                        : read_solids(root, scene.gravity);
  if (infer_tank) scene.infer_container = TankInference::Required;
  scene.diffuse = read_diffuse_params(root.child("diffuse"), scene.fluid, scene.gravity);
  const ParamReader output = root.child("output");
  scene.write_bgeo = output.boolean(k::output::bgeo);
  scene.write_fluid_bgeo = output.boolean(k::output::fluid_bgeo);
  scene.write_vdb = output.boolean(k::output::vdb);
  scene.fog_voxel = float(output.number(k::output::fog));
  if (scene.write_fluid_bgeo && scene.source != FluidSourceKind::Solver)
    output.fail_at("fluid_bgeo", "only scenes with fluid.source \"solver\" write fluid frames");

  // The values the run uses (defaults included), so a key written at its default is no change.
  Json fluid_keys = root.effective("fluid");
  if (fluid_keys.is_object()) {
    fluid_keys.erase("frames");
    fluid_keys["particles"] = scene.flip_particles ? "flip" : "sph";  // what "auto" decided, not the word
    if (scene.source == FluidSourceKind::Files) {
      // The files by what they are, not by how the path was typed (relative, absolute, $F4 or %04d).
      fluid_keys["files"] = canonical_frame_pattern(scene.file_pattern);
      if (!reads_vdb_grids(scene.file_pattern)) fluid_keys.erase("vdb_grid");  // ignored: no change of input
    }
  }
  Json keys = {{"gravity", root.effective("gravity")}, {"fluid", fluid_keys}, {"solids", root.effective("solids")}};
  // What "auto" and a Mantaflow config decided shapes the frames as much as the keys do.
  if (scene.read.up != UpAxis::Y || scene.velocity_scale != float(fluid.number(k::fluid::velocity_scale)) ||
      !scene.read.stored_masses || scene.fluid.fps != fluid.number(k::fluid::fps)) {
    keys["fluid_import"] = {{"up_axis", up_axis_name(scene.read.up)}, {"velocity_scale", scene.velocity_scale}};
    if (!scene.read.stored_masses) keys["fluid_import"]["masses"] = "implied";
    if (scene.fluid.fps != fluid.number(k::fluid::fps)) keys["fluid_import"]["fps"] = scene.fluid.fps;
  }
  if (scene.source == FluidSourceKind::Solver && scene.solids.any_dynamic())
    keys["spume_bodies_generation"] = kBodiesGeneration;
  // No output.* key: the exports are made from the caches, with records of their own
  // (io/frame_export.h), so turning one on or off re-simulates nothing.
  scene.fluid_keys = with_generation(keys, kFluidCacheGeneration);
  keys["diffuse"] = root.effective("diffuse");
  keys["domain"] = root.effective("domain");
  scene.diffuse_keys = with_generation(keys, kDiffuseCacheGeneration);
  return scene;
}

Aabb tank_with_air_above(const Solid& tank) {
  Aabb box;
  box.extend(tank.min);
  Vec3f top = tank.max;
  if (tank.open_top) top[tank.up_axis] += tank.max[tank.up_axis] - tank.min[tank.up_axis];
  box.extend(top);
  return box;
}

Aabb default_domain(const SimScene& scene, const Aabb& fluid_bounds) {
  Aabb box;
  for (const Solid& s : scene.solids.solids())
    if (s.kind == Solid::Kind::Tank) {
      Aabb reach = tank_with_air_above(s);
      if (s.open_top)  // spray thrown over the rim falls beside the tank, to the ground at its floor
        for (int a = 0; a < 3; ++a)
          if (a != s.up_axis) {
            const float height = s.max[s.up_axis] - s.min[s.up_axis];
            reach.min[a] -= height, reach.max[a] += height;
          }
      box.extend(reach);
    }
  if (!box.empty()) return box;
  box = fluid_bounds;
  if (box.empty()) return box;
  const Vec3f margin = (box.max - box.min).cwiseMax(Vec3f::Constant(8.0f * scene.fluid.support_radius));
  box.min -= margin;
  box.max += margin;
  return box;
}

}  // namespace spume
