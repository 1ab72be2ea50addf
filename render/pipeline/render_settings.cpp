#include "render_settings.h"

#include <cmath>

#include <filesystem>

#include "core/error.h"
#include "io/frame_pattern.h"

namespace spume {
namespace {

struct LookDefault {
  const char* key;
  float radius_in_r;
  Vec3f color;
};
// Spray smaller than foam, so it reads sharper (the paper's Sec. 4); bubbles in between, bluish.
const LookDefault kLookDefaults[kDiffuseTypeCount] = {
    {"spray", 0.3f, Vec3f(0.92f, 0.95f, 1.0f)},
    {"foam", 0.5f, Vec3f(0.95f, 0.95f, 0.95f)},
    {"bubble", 0.4f, Vec3f(0.80f, 0.90f, 1.0f)},
};

Vec3f colour(const ParamReader& r, const std::string& key, const Vec3f& fallback) {
  const Vec3f c = r.vec3(key, fallback);
  if (!(c.array() >= 0.0f).all() || !(c.array() <= 100.0f).all())
    r.fail_at(key, "expected linear RGB [r, g, b] with each channel in [0, 100]");
  return c;
}

std::vector<CameraKey> read_camera(const ParamReader& render) {
  if (!render.has("camera")) return {};
  const ParamReader cam = render.child("camera");
  auto read_key = [](const ParamReader& k, double time) {
    CameraKey key;
    key.time = time;
    if (!k.has("position")) k.fail_at("position", "missing: the camera position [x, y, z] in m");
    key.position = k.vec3("position", key.position);
    key.target = k.vec3("target", key.target);
    key.fov_y_degrees = float(k.number_in("fov", key.fov_y_degrees, 1.0, 170.0));
    if ((key.position - key.target).norm() <= 0.0f) k.fail_at("target", "must differ from the position");
    return key;
  };
  std::vector<CameraKey> keys;
  if (cam.has("keys")) {
    for (const ParamReader& k : cam.array_of_objects("keys")) {
      if (!k.has("time")) k.fail_at("time", "missing: the key's time in s");
      const double t = k.number("time", 0.0);
      if (!keys.empty() && !(t > keys.back().time))
        k.fail_at("time", str("camera key times must increase; ", t, " follows ", keys.back().time));
      keys.push_back(read_key(k, t));
    }
    if (keys.empty()) cam.fail_at("keys", "expected at least one key {\"time\", \"position\", \"target\", \"fov\"}");
  } else {
    keys.push_back(read_key(cam, 0.0));
  }
  return keys;
}

// ---- Keys of the water look (issue 15), kept together so they move as one block. ----
//   render.surface_smoothing         iterations  0..100  default 8     Taubin smoothing of the surface mesh
//   render.water.refraction          1           0..1    default 1     0: straight-through view; 1: physical bend
//   render.water.scene_reflections   bool                default true  reflect ground and solids (screen space)
void read_look_keys(const ParamReader& render, RenderSettings& s) {
  s.surface.smoothing = int(render.integer_in("surface_smoothing", s.surface.smoothing, 0, 100));
  const ParamReader water = render.child("water");
  s.water.refraction = float(water.number_in("refraction", s.water.refraction, 0.0, 1.0));
  s.water.scene_reflections = water.boolean("scene_reflections", s.water.scene_reflections);
}
// ---- end of the water look's keys ----

}  // namespace

bool RenderSettings::draws_diffuse() const {
  for (const DiffuseLook& l : volume.look)
    if (l.radius > 0.0f) return true;
  return false;
}

RenderSettings read_render_settings(const ParamReader& render, float particle_radius) {
  RenderSettings s;
  if (render.has("resolution")) {
    const Json v = render.raw("resolution");
    auto whole = [](const Json& x) { return x.is_number() && x.get<double>() == std::floor(x.get<double>()); };
    if (!v.is_array() || v.size() != 2 || !whole(v[0]) || !whole(v[1]) || v[0].get<double>() < 1 ||
        v[1].get<double>() < 1 || v[0].get<double>() > 16384 || v[1].get<double>() > 16384)
      render.fail_at("resolution", str("expected [width, height] in whole pixels from 1 to 16384, found ", v.dump()));
    s.width = v[0].get<int>();
    s.height = v[1].get<int>();
  }
  s.camera = read_camera(render);
  s.draw_surface = render.boolean("surface", s.draw_surface);
  s.draw_solids = render.boolean("solids", s.draw_solids);
  s.supersample = int(render.integer_in("supersample", s.supersample, 1, 4));

  s.surface.particle_radius = particle_radius;
  s.surface.cell_factor = float(render.number_in("surface_cell", s.surface.cell_factor, 0.25, 4.0));
  s.surface.validate("render.surface_cell");

  VolumeSettings& v = s.volume;
  v.samples_per_pixel = int(render.integer_in("spp", 1, 1, 1024));
  const double seed = render.number_in("seed", 0.0, 0.0, 4294967295.0);
  if (seed != std::floor(seed)) render.fail_at("seed", "expected a whole number");
  v.seed = uint64_t(seed);
  v.integrator = render.choice("integrator", "exact", {"exact", "march"}) == "exact" ? VolumeIntegrator::Exact
                                                                                     : VolumeIntegrator::March;
  v.march_step = float(render.non_negative("march_step", 0.0));
  v.alpha = float(render.non_negative("alpha", v.alpha));
  for (int t = 0; t < kDiffuseTypeCount; ++t) {
    const LookDefault& d = kLookDefaults[t];
    const ParamReader look = render.child(d.key);
    v.look[size_t(t)].radius = float(look.number_in("radius", d.radius_in_r * particle_radius, 0.0, 1e3));
    v.look[size_t(t)].color = colour(look, "color", d.color);
  }

  const ParamReader water = render.child("water");
  s.water.absorption = water.vec3("absorption", s.water.absorption);
  if (!(s.water.absorption.array() >= 0.0f).all())
    water.fail_at("absorption", "expected [r, g, b] in 1/m, each >= 0");
  s.water.ior = float(water.number_in("ior", s.water.ior, 1.0, 3.0));
  s.water.roughness = float(water.number_in("roughness", s.water.roughness, 0.001, 1.0));
  s.water.deep_color = colour(water, "deep_color", s.water.deep_color);
  // One absorption for both passes: what the OSMesa pass tints, the volume pass dims bubbles by.
  v.water_sigma = s.water.absorption;

  read_look_keys(render, s);

  s.environment.ground = render.boolean("ground", s.environment.ground);
  if (auto g = render.optional_number("ground_height")) s.ground_height = float(*g);
  if (render.has("sun_direction")) {
    const Vec3f d = render.vec3("sun_direction", s.environment.sun_direction);
    if (!(d.norm() > 0.0f)) render.fail_at("sun_direction", "expected a non-zero direction [x, y, z] towards the sun");
    s.environment.sun_direction = d.normalized();
  }
  s.frame_pattern = render.text("frames", s.frame_pattern);
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
