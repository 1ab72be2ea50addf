#include "render/gl/environment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace spume {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

float smooth(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Average sky radiance over the upper hemisphere (cosine-weighted, roughly), scaled down: the open
// sky of a real scene is partly blocked, and a full-strength blue dome turns shadows blue.
Vec3f sky_ambient(const Environment& e) { return 0.6f * (0.6f * e.sky_zenith + 0.4f * e.sky_horizon); }

}  // namespace

// Keep every formula below in step with environment_glsl().

Vec3f Environment::sky(const Vec3f& d, bool with_sun_disc) const {
  const Vec3f s = sun_direction;
  if (d.y() < 0.0f) {
    // Ground at infinity, lost in haze at the horizon.
    const Vec3f far_ground = ground_albedo.cwiseProduct(irradiance(Vec3f::UnitY())) / kPi;
    return sky_horizon + smooth(0.0f, 0.12f, -d.y()) * (far_ground - sky_horizon);
  }
  const float t = std::pow(1.0f - d.y(), 3.0f);  // 1 at the horizon, 0 at the zenith
  Vec3f c = sky_zenith + t * (sky_horizon - sky_zenith);
  const float mu = std::max(d.dot(s), 0.0f);
  c += sun_irradiance * (0.05f * std::pow(mu, 8.0f) + 0.2f * std::pow(mu, 120.0f));  // glow around the sun
  if (with_sun_disc && mu > std::cos(sun_angular_radius))
    c += sun_irradiance / (kPi * sun_angular_radius * sun_angular_radius);
  return c;
}

Vec3f Environment::irradiance(const Vec3f& n, float sun_visibility) const {
  const Vec3f amb = sky_ambient(*this);
  const Vec3f bounce = ground_albedo.cwiseProduct(sun_irradiance * std::max(sun_direction.y(), 0.0f) + kPi * amb) / kPi;
  const float up = 0.5f + 0.5f * n.y();
  return sun_irradiance * (sun_visibility * std::max(n.dot(sun_direction), 0.0f)) +
         kPi * (up * amb + (1.0f - up) * bounce);
}

Vec3f Environment::ground_radiance(const Vec3f& p, const Vec3f& eye, float sun_visibility) const {
  float shade = 1.0f;
  if (ground_tile > 0.0f) {
    const float c = std::floor(p.x() / ground_tile) + std::floor(p.z() / ground_tile);
    shade = c - 2.0f * std::floor(0.5f * c) < 0.5f ? 1.0f : 0.82f;
  }
  const Vec3f lit = shade * ground_albedo.cwiseProduct(irradiance(Vec3f::UnitY(), sun_visibility)) / kPi;
  const float haze = 1.0f - std::exp(-(p - eye).norm() / haze_distance);
  return lit + haze * (sky_horizon - lit);
}

const std::string& environment_glsl() {
  static const std::string text = R"GLSL(
layout(std140, binding = 0) uniform Env {
  vec4 sun_dir;        // xyz towards the sun; w = cos(sun angular radius)
  vec4 sun_irr;        // rgb; w = ground height (m)
  vec4 zenith;         // rgb
  vec4 horizon;        // rgb
  vec4 ground_albedo;  // rgb; w = checker tile (m)
  vec4 env_params;     // x = haze distance (m), y = ground drawn, z = sun disc solid-angle factor
  vec4 water_abs;      // rgb 1/m; w = ior
  vec4 water_deep;     // rgb; w = GGX alpha
  vec4 water_params;   // x = refraction strength, y = scene reflections on
};
const float PI = 3.14159265;

vec3 env_ambient() { return 0.6 * (0.6 * zenith.rgb + 0.4 * horizon.rgb); }

vec3 env_irradiance(vec3 n, float sun_visibility) {
  vec3 amb = env_ambient();
  vec3 bounce = ground_albedo.rgb * (sun_irr.rgb * max(sun_dir.y, 0.0) + PI * amb) / PI;
  float up = 0.5 + 0.5 * n.y;
  return sun_irr.rgb * (sun_visibility * max(dot(n, sun_dir.xyz), 0.0)) + PI * (up * amb + (1.0 - up) * bounce);
}

vec3 env_sky(vec3 d, bool with_sun_disc) {
  if (d.y < 0.0) {
    vec3 far_ground = ground_albedo.rgb * env_irradiance(vec3(0.0, 1.0, 0.0), 1.0) / PI;
    return horizon.rgb + smoothstep(0.0, 0.12, -d.y) * (far_ground - horizon.rgb);
  }
  float t = pow(1.0 - d.y, 3.0);
  vec3 c = zenith.rgb + t * (horizon.rgb - zenith.rgb);
  float mu = max(dot(d, sun_dir.xyz), 0.0);
  c += sun_irr.rgb * (0.05 * pow(mu, 8.0) + 0.2 * pow(mu, 120.0));
  if (with_sun_disc && mu > sun_dir.w) c += sun_irr.rgb * env_params.z;
  return c;
}

vec3 env_ground(vec3 p, vec3 eye, float sun_visibility) {
  float shade = 1.0;
  if (ground_albedo.w > 0.0) {
    float c = floor(p.x / ground_albedo.w) + floor(p.z / ground_albedo.w);
    shade = c - 2.0 * floor(0.5 * c) < 0.5 ? 1.0 : 0.82;
  }
  vec3 lit = shade * ground_albedo.rgb * env_irradiance(vec3(0.0, 1.0, 0.0), sun_visibility) / PI;
  float haze = 1.0 - exp(-length(p - eye) / env_params.x);
  return lit + haze * (horizon.rgb - lit);
}
)GLSL";
  return text;
}

EnvBlock env_block(const Environment& e, const WaterLook& w) {
  EnvBlock b{};
  auto put = [](float* dst, const Vec3f& v, float fourth) {
    dst[0] = v.x(), dst[1] = v.y(), dst[2] = v.z(), dst[3] = fourth;
  };
  put(b.sun_dir, e.sun_direction.normalized(), std::cos(e.sun_angular_radius));
  put(b.sun_irr, e.sun_irradiance, e.ground_height);
  put(b.zenith, e.sky_zenith, 0);
  put(b.horizon, e.sky_horizon, 0);
  put(b.ground_albedo, e.ground_albedo, e.ground_tile);
  put(b.params,
      Vec3f(e.haze_distance, e.ground ? 1.0f : 0.0f, 1.0f / (kPi * e.sun_angular_radius * e.sun_angular_radius)), 0);
  put(b.water_abs, w.absorption, w.ior);
  put(b.water_deep, w.deep_color, w.roughness);
  put(b.water, Vec3f(w.refraction, w.scene_reflections ? 1.0f : 0.0f, 0), 0);
  return b;
}

}  // namespace spume
