#include "render/frame/render_settings.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include <filesystem>

#include "sim/core/error.h"
#include "sim/io/frame_pattern.h"
#include "render/keys/render_keys.h"

namespace spume {
namespace {

namespace k = keys::render;

// The three diffuse types' keys, in DiffuseType order.
struct LookKeys {
  const KeySpec& radius;
  const KeySpec& color;
};
const LookKeys kLookKeys[kDiffuseTypeCount] = {
    {k::spray_radius, k::spray_color}, {k::foam_radius, k::foam_color}, {k::bubble_radius, k::bubble_color}};

ParamReader look_reader(const ParamReader& render, const KeySpec& key) {
  const std::string path = key.path;  // "render.spray.radius" -> the "spray" object
  const size_t last = path.rfind('.'), before = path.rfind('.', last - 1);
  return render.child(path.substr(before + 1, last - before - 1));
}

std::vector<CameraKey> read_camera(const ParamReader& render) {
  if (!render.has(k::camera.name())) return {};
  const ParamReader cam = render.child(k::camera.name());
  auto read_key = [](const ParamReader& r, double time, const KeySpec& position, const KeySpec& target,
                     const KeySpec& fov) {
    CameraKey key;
    key.time = time;
    key.position = r.vec3(position);
    key.target = r.vec3(target);
    key.fov_y_degrees = float(r.number(fov));
    if ((key.position - key.target).norm() <= 0.0f) r.fail_at("target", "must differ from the position");
    return key;
  };
  std::vector<CameraKey> keys;
  if (cam.has(k::camera_keys.name())) {
    for (const ParamReader& r : cam.array_of_objects(k::camera_keys.name())) {
      const double t = r.number(k::key_time);
      if (!keys.empty() && !(t > keys.back().time))
        r.fail_at("time", str("camera key times must increase; ", t, " follows ", keys.back().time));
      keys.push_back(read_key(r, t, k::key_position, k::key_target, k::key_fov));
    }
    if (keys.empty()) cam.fail_at("keys", "expected at least one key {\"time\", \"position\", \"target\", \"fov\"}");
  } else {
    keys.push_back(read_key(cam, 0.0, k::camera_position, k::camera_target, k::camera_fov));
  }
  return keys;
}

}  // namespace

bool RenderSettings::draws_diffuse() const {
  for (const DiffuseLook& l : volume.look)
    if (l.radius > 0.0f) return true;
  return false;
}

std::string RenderSettings::exr_pattern() const {
  return std::filesystem::path(frame_pattern).replace_extension(".exr").string();
}

RenderSettings read_render_settings(const ParamReader& render, float particle_radius) {
  RenderSettings s;
  if (render.has(k::resolution.name())) {
    const Json v = render.raw(k::resolution.name());
    auto whole = [](const Json& x) { return x.is_number() && x.get<double>() == std::floor(x.get<double>()); };
    const bool ok = v.is_array() && v.size() == 2 && whole(v[0]) && whole(v[1]) &&
                    out_of_range(k::resolution, v[0].get<double>()).empty() &&
                    out_of_range(k::resolution, v[1].get<double>()).empty();
    if (!ok)
      render.fail_at("resolution", str("expected [width, height] in whole pixels ", range_description(k::resolution),
                                       ", found ", v.dump()));
    s.width = v[0].get<int>();
    s.height = v[1].get<int>();
  }
  s.camera = read_camera(render);
  s.draw_surface = render.boolean(k::surface);
  s.draw_solids = render.boolean(k::solids);
  s.supersample = int(render.integer(k::supersample));

  s.surface.particle_radius = particle_radius;
  s.surface.cell_factor = float(render.number(k::surface_cell));
  s.surface.smoothing = int(render.integer(k::surface_smoothing));
  s.surface.validate("render.surface_cell");

  VolumeSettings& v = s.volume;
  v.samples_per_pixel = int(render.integer(k::spp));
  v.seed = uint64_t(render.integer(k::seed));
  v.integrator = render.choice(k::integrator) == "exact" ? VolumeIntegrator::Exact : VolumeIntegrator::March;
  v.march_step = float(render.number(k::march_step));
  v.alpha = float(render.number(k::alpha));
  v.shutter = float(render.number(k::shutter));
  if (v.shutter > 0.0f && v.integrator == VolumeIntegrator::March)
    render.fail_at("shutter", str(v.shutter, ": motion blur integrates each particle along its path exactly and needs "
                                  "render.integrator \"exact\"; set render.shutter to 0 to march Eq. 9 as written"));
  for (int t = 0; t < kDiffuseTypeCount; ++t) {
    const ParamReader look = look_reader(render, kLookKeys[t].radius);
    v.look[size_t(t)].radius = float(look.number(kLookKeys[t].radius, particle_radius));
    v.look[size_t(t)].color = look.vec3(kLookKeys[t].color);
  }

  const ParamReader water = render.child("water");
  s.water.absorption = water.vec3(k::water_absorption);
  s.water.ior = float(water.number(k::water_ior));
  s.water.roughness = float(water.number(k::water_roughness));
  s.water.deep_color = water.vec3(k::water_deep_color);
  s.water.refraction = float(water.number(k::water_refraction));
  s.water.scene_reflections = water.boolean(k::water_scene_reflections);
  // One absorption for both passes: what the OSMesa pass tints, the volume pass dims bubbles by.
  v.water_sigma = s.water.absorption;

  s.environment.ground = render.boolean(k::ground);
  if (render.has(k::ground_height.name())) s.ground_height = float(render.number(k::ground_height));
  const Vec3f sun = render.vec3(k::sun_direction);
  if (!(sun.norm() > 0.0f)) render.fail_at("sun_direction", "expected a non-zero direction [x, y, z] towards the sun");
  s.environment.sun_direction = sun.normalized();
  s.frame_pattern = render.text(k::frames.name(), k::frames.choices);
  if (!is_frame_pattern(s.frame_pattern))
    render.fail_at("frames", str("\"", s.frame_pattern,
                                 "\" needs one frame placeholder (%04d, %d or ####), e.g. \"frames/%04d.png\""));
  try {
    expand_frame_pattern(s.frame_pattern, 0);
  } catch (const Error& e) {
    render.fail_at("frames", e.what());
  }
  if (std::filesystem::path(s.frame_pattern).is_absolute() || s.frame_pattern.find("..") != std::string::npos)
    render.fail_at("frames", str("\"", s.frame_pattern, "\" must stay inside the scene's output folder"));
  // Frames are PNG: a name that says otherwise would hold bytes its readers cannot open.
  std::string extension = std::filesystem::path(s.frame_pattern).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (extension != ".png")
    render.fail_at("frames", str("\"", s.frame_pattern, "\" ends in \"", extension.empty() ? "(no extension)" : extension,
                                 "\"; spume writes PNG frames, so the name must end in .png, e.g. \"frames/%04d.png\""));
  s.exr = render.boolean(k::exr);
  return s;
}

CameraKey auto_camera(const Aabb& bounds, const Vec3f& up, float fov_y_degrees, float aspect) {
  CameraKey key;
  key.fov_y_degrees = fov_y_degrees;
  const Vec3f centre = 0.5f * (bounds.min + bounds.max);
  const float radius = std::max(0.5f * (bounds.max - bounds.min).norm(), 1e-3f);
  // An elevated three-quarter view: from the side of the bounds, 30 degrees above the horizon.
  const Vec3f side = std::abs(up.dot(Vec3f::UnitZ())) < 0.9f ? Vec3f::UnitZ() : Vec3f::UnitY();
  const Vec3f across = up.cross(side).normalized();
  const Vec3f horizontal = (side - side.dot(up) * up).normalized() * 0.87f + across * 0.49f;
  const Vec3f direction = (horizontal.normalized() * std::cos(0.52f) + up * std::sin(0.52f)).normalized();
  const float half_fov = 0.5f * float(fov_y_degrees * M_PI / 180.0);
  const float fit = std::min(std::tan(half_fov), std::tan(half_fov) * aspect);
  key.target = centre;
  key.position = centre + direction * (radius / std::sin(std::atan(fit)) * 1.05f);
  return key;
}

}  // namespace spume
