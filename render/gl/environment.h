#pragma once
// The sunny-day look: an analytic sky with a sun, a ground plane, and the water material. One model,
// written twice side by side in environment.cpp -- as GLSL for the surface pass and as C++ for tests
// and for the background when no GL context is needed. Radiance is linear RGB in display units: 1 is
// white on screen; a white diffuse surface facing a high sun reads about 0.8.
#include <string>

#include "sim/core/vec.h"
#include "render/keys/render_keys.h"

namespace spume {

struct Environment {
  Vec3f sun_direction = declared_vec3<Vec3f>(keys::render::sun_direction).normalized();  // unit, towards the sun
  Vec3f sun_irradiance = Vec3f(2.3f, 2.15f, 1.95f);  // on a surface facing the sun; warm white
  float sun_angular_radius = 0.012f;                  // rad: the disc in the sky (about 2x the real sun)
  Vec3f sky_zenith = Vec3f(0.10f, 0.22f, 0.55f);      // radiance straight up
  Vec3f sky_horizon = Vec3f(0.55f, 0.68f, 0.85f);     // radiance at the horizon (haze)
  bool ground = keys::render::ground.value[0] != 0.0;  // draw a ground plane (when the scene has no floor)
  float ground_height = 0.0f;                         // m, the plane y = ground_height
  Vec3f ground_albedo = Vec3f(0.58f, 0.48f, 0.34f);   // sand
  float ground_tile = 0.5f;                           // m, faint checker for scale and refraction; 0: plain
  float haze_distance = 120.0f;                       // m: the ground fades to the horizon colour

  // Radiance seen along unit direction d. Below the horizon: the lit ground at infinity (haze).
  Vec3f sky(const Vec3f& d, bool with_sun_disc) const;
  // Irradiance on a surface with unit normal n, from the sun (times its visibility in [0, 1]:
  // shadows) and the sky dome and ground.
  Vec3f irradiance(const Vec3f& n, float sun_visibility = 1.0f) const;
  // Radiance of the ground plane at point p (y = ground_height), seen from `eye`.
  Vec3f ground_radiance(const Vec3f& p, const Vec3f& eye, float sun_visibility = 1.0f) const;
};

struct WaterLook {
  float ior = float(keys::render::water_ior.value[0]);  // refractive index (Schlick F0 = 0.02)
  // 1/m per channel, Beer-Lambert. About 5x clear sea water, so tank-sized scenes (0.1-1 m deep) read
  // as water; use the same value for the volume pass's water_sigma.
  Vec3f absorption = declared_vec3<Vec3f>(keys::render::water_absorption);
  Vec3f deep_color = declared_vec3<Vec3f>(keys::render::water_deep_color);  // radiance through an infinite depth
  float roughness = float(keys::render::water_roughness.value[0]);  // GGX alpha of the sun's highlight
  float refraction = float(keys::render::water_refraction.value[0]);  // 0: straight through; 1: physical bend
  bool scene_reflections = keys::render::water_scene_reflections.value[0] != 0.0;  // false: the sky only
};

// The GLSL (450) declarations of the environment: a uniform block `Env` at binding 0 and the
// functions env_sky, env_irradiance, env_ground, matching the C++ above (visibility as an argument).
const std::string& environment_glsl();

// The std140 contents of the `Env` block (see environment.cpp for the layout).
struct EnvBlock {
  float sun_dir[4], sun_irr[4], zenith[4], horizon[4], ground_albedo[4];
  float params[4], water_abs[4], water_deep[4], water[4];
};
EnvBlock env_block(const Environment& env, const WaterLook& water);

}  // namespace spume
