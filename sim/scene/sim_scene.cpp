#include "sim_scene.h"

#include "core/error.h"
#include "scene/diffuse_params_reader.h"
#include "scene/solids_reader.h"

namespace spume {
namespace {

bool is_name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'; }

}  // namespace

SimScene read_sim_scene(const ParamReader& root, const std::filesystem::path& scene_dir,
                        const std::string& default_name) {
  SimScene scene;
  scene.name = root.text("name", default_name);
  if (scene.name.empty() || !std::all_of(scene.name.begin(), scene.name.end(), is_name_char) || scene.name[0] == '.')
    root.fail_at("name", str("\"", scene.name, "\" is not a usable folder name; use letters, digits, _ - ."));
  scene.gravity = root.vec3("gravity", scene.gravity);

  const ParamReader fluid = root.child("fluid");
  const std::string source = fluid.choice("source", "files", {"files", "solver"});
  scene.source = source == "files" ? FluidSourceKind::Files : FluidSourceKind::Solver;
  if (!fluid.has("radius")) fluid.fail_at("radius", "missing: the fluid particle radius in m is required");
  scene.fluid.particle_radius = float(fluid.positive("radius", 0.0));
  scene.fluid.support_radius = float(fluid.positive("support_radius", 4.0 * scene.fluid.particle_radius));
  if (scene.fluid.support_radius < scene.fluid.particle_radius)
    fluid.fail_at("support_radius", str("value ", scene.fluid.support_radius, " is below the particle radius ",
                                        scene.fluid.particle_radius, "; the usual choice is 4 x radius"));
  scene.fluid.fps = fluid.number_in("fps", 50.0, 1e-3, 1e5);
  scene.fluid.rest_density = float(fluid.positive("rest_density", 1000.0));
  if (scene.source == FluidSourceKind::Files) {
    const auto files = fluid.optional_text("files");
    if (!files) fluid.fail_at("files", "missing: a file pattern such as \"cache/ParticleData_Fluid_%d.bgeo\"");
    const std::filesystem::path pattern(*files);
    scene.file_pattern = pattern.is_absolute() ? pattern.string() : (scene_dir / pattern).lexically_normal().string();
  }
  if (fluid.has("frames")) {
    const auto [a, b] = fluid.range("frames", {0, 1});
    if (a < 0 || a != std::floor(a) || b != std::floor(b))
      fluid.fail_at("frames", "expected [first, last] whole frame numbers >= 0");
    scene.frames = std::make_pair(int(a), int(b));
  }

  const ParamReader domain = root.child("domain");
  if (root.has("domain")) {
    scene.domain.min = domain.vec3("min", Vec3f::Zero());
    scene.domain.max = domain.vec3("max", Vec3f::Zero());
    if (!(scene.domain.min.array() < scene.domain.max.array()).all())
      root.fail_at("domain", "min must be below max on every axis");
  }

  scene.solids = read_solids(root, scene.gravity);
  scene.diffuse = read_diffuse_params(root.child("diffuse"), scene.fluid, scene.gravity);
  scene.write_bgeo = root.child("output").boolean("bgeo", false);
  return scene;
}

Aabb default_domain(const SimScene& scene, const FluidFrame& first) {
  Aabb box;
  for (const Solid& s : scene.solids.solids())
    if (s.kind == Solid::Kind::Tank) {
      box.extend(s.min);
      Vec3f top = s.max;
      if (s.open_top) top[s.up_axis] += s.max[s.up_axis] - s.min[s.up_axis];
      box.extend(top);
    }
  if (!box.empty()) return box;
  for (const Vec3f& p : first.positions) box.extend(p);
  if (box.empty()) return box;
  const Vec3f margin = (box.max - box.min).cwiseMax(Vec3f::Constant(8.0f * scene.fluid.support_radius));
  box.min -= margin;
  box.max += margin;
  return box;
}

}  // namespace spume
