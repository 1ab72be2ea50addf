#include "surface_shaders.h"

#include "environment.h"
#include "sun_shadow.h"

namespace spume::shaders {
namespace {

const char* kHeader = R"GLSL(#version 450 core
layout(std140, binding = 1) uniform Frame {
  mat4 view_proj;
  mat4 inv_view;
  mat4 inv_view_proj;
  vec4 eye;
  vec4 proj;
  vec4 viewport;
  mat4 sun_view_proj;
  vec4 shadow;
};
float positive_infinity() { return uintBitsToFloat(0x7F800000u); }
)GLSL";

std::string fragment_header() { return std::string(kHeader) + environment_glsl() + sun_shadow_glsl(); }

}  // namespace

std::string sky_vertex() {
  return std::string(kHeader) + R"GLSL(
out vec2 v_ndc;
void main() {
  // One triangle covering the screen, on the far plane.
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;
  v_ndc = p;
  gl_Position = vec4(p, 1.0, 1.0);
}
)GLSL";
}

std::string sky_fragment() {
  return fragment_header() + R"GLSL(
in vec2 v_ndc;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out float o_depth;
void main() {
  vec4 far_point = inv_view_proj * vec4(v_ndc, 1.0, 1.0);
  vec3 d = normalize(far_point.xyz / far_point.w - eye.xyz);
  o_colour = vec4(env_sky(d, true), 1.0);
  o_depth = positive_infinity();
}
)GLSL";
}

std::string mesh_vertex() {
  return std::string(kHeader) + R"GLSL(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform vec3 u_offset;  // m, rigid translation of a moving solid
out vec3 v_world;
out vec3 v_normal;
out float v_depth;
void main() {
  v_world = a_position + u_offset;
  v_normal = a_normal;
  gl_Position = view_proj * vec4(v_world, 1.0);
  v_depth = gl_Position.w;  // = -z_view for a perspective projection
}
)GLSL";
}

std::string opaque_fragment() {
  return fragment_header() + R"GLSL(
in vec3 v_world;
in vec3 v_normal;
in float v_depth;
uniform vec3 u_albedo;
uniform int u_ground;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out float o_depth;
void main() {
  // llvmpipe runs both sides of a branch: one shadow lookup serves the ground and the solids.
  bool ground = u_ground == 1;
  vec3 n = normalize(v_normal);
  if (dot(n, eye.xyz - v_world) < 0.0) n = -n;  // two-sided: a tank is seen from inside
  if (ground) n = vec3(0.0, 1.0, 0.0);
  float visibility = sun_visibility(v_world, n);
  vec3 c = ground ? env_ground(v_world, eye.xyz, visibility) : u_albedo * env_irradiance(n, visibility) / PI;
  o_colour = vec4(c, 1.0);
  o_depth = v_depth;
}
)GLSL";
}

std::string depth_fragment() {
  return std::string(kHeader) + R"GLSL(
in float v_depth;
layout(location = 0) out float o_depth;
void main() { o_depth = v_depth; }
)GLSL";
}

std::string water_fragment() {
  return fragment_header() + R"GLSL(
in vec3 v_world;
in vec3 v_normal;
in float v_depth;
layout(binding = 0) uniform sampler2D u_behind_colour;  // opaque scene and sky, linear RGB
layout(binding = 1) uniform sampler2D u_behind_depth;   // its linear depth
layout(binding = 2) uniform sampler2D u_back_depth;     // linear depth of the water's back faces
layout(location = 0) out vec4 o_colour;
layout(location = 1) out float o_depth;

ivec2 texel(vec2 uv) { return clamp(ivec2(uv * viewport.xy), ivec2(0), ivec2(viewport.xy) - 1); }
// Where the view ray through this texel leaves the water: its back face or the opaque scene.
float exit_depth(ivec2 t) { return min(texelFetch(u_behind_depth, t, 0).r, texelFetch(u_back_depth, t, 0).r); }
vec3 world_at(vec2 uv, float depth) {
  vec2 ndc = uv * 2.0 - 1.0;
  return (inv_view * vec4(ndc.x / proj.x * depth, ndc.y / proj.y * depth, -depth, 1.0)).xyz;
}

void main() {
  vec3 V = normalize(eye.xyz - v_world);
  vec3 N = normalize(v_normal);
  // Smooth normals can face away near silhouettes: bend them back just enough.
  float ndv_raw = dot(N, V);
  if (ndv_raw < 0.02) N = normalize(N + (0.02 - ndv_raw) * V);
  float ndv = clamp(dot(N, V), 0.0, 1.0);
  float ior = water_abs.w;
  float f0 = (ior - 1.0) * (ior - 1.0) / ((ior + 1.0) * (ior + 1.0));
  float fresnel = f0 + (1.0 - f0) * pow(1.0 - ndv, 5.0);

  // Transmission: follow the refracted ray for the water thickness seen along the view ray, look up
  // the opaque scene where it lands, and absorb along the path (Beer-Lambert per channel).
  vec2 uv = gl_FragCoord.xy * viewport.zw;
  float ray_scale = length(eye.xyz - v_world) / v_depth;  // path length per unit of view depth
  float straight = max(exit_depth(texel(uv)) - v_depth, 0.0) * ray_scale;
  straight = min(straight, 1000.0);
  // Refracted path to the same depth below the surface (exact for a bottom parallel to the surface,
  // e.g. a tank floor under calm water): straight * cos(incidence) / cos(refraction).
  vec3 T = refract(-V, N, 1.0 / ior);
  float bent_length = straight * ndv / max(-dot(T, N), 1e-3);
  vec3 target = mix(v_world - V * straight, v_world + T * bent_length, water_params.x);
  vec4 clip = view_proj * vec4(target, 1.0);
  vec2 uv_r = clip.w > 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : uv;
  float exit_r = exit_depth(texel(uv_r));
  if (exit_r <= v_depth) {  // something in front of the water there: look straight through
    uv_r = uv;
    exit_r = exit_depth(texel(uv));
  }
  float path = isinf(exit_r) ? 1000.0 : min(distance(v_world, world_at(uv_r, exit_r)), 1000.0);
  vec3 transmittance = exp(-water_abs.rgb * path);
  vec3 behind = texelFetch(u_behind_colour, texel(uv_r), 0).rgb;
  vec3 transmitted = behind * transmittance + water_deep.rgb * (1.0 - transmittance);

  // Reflection of the analytic sky (the sun disc comes from the highlight below instead).
  vec3 reflected = env_sky(reflect(-V, N), false);

  // The sun's highlight: GGX distribution, Smith-Schlick visibility, Schlick Fresnel.
  vec3 S = sun_dir.xyz;
  float ndl = dot(N, S);
  vec3 highlight = vec3(0.0);
  if (ndl > 0.0) {
    vec3 H = normalize(V + S);
    float a2 = water_deep.w * water_deep.w, ndh = max(dot(N, H), 0.0);
    float denom = ndh * ndh * (a2 - 1.0) + 1.0;
    float D = a2 / (PI * denom * denom);
    float k = 0.5 * water_deep.w;
    float G = ndv / (ndv * (1.0 - k) + k) * ndl / (ndl * (1.0 - k) + k);
    float Fh = f0 + (1.0 - f0) * pow(1.0 - max(dot(H, V), 0.0), 5.0);
    highlight = sun_irr.rgb * D * G * Fh / (4.0 * max(ndv, 1e-3)) * sun_visibility(v_world, N);
  }
  o_colour = vec4(fresnel * reflected + (1.0 - fresnel) * transmitted + highlight, 1.0);
  o_depth = v_depth;
}
)GLSL";
}

std::string downsample_fragment() {
  return std::string(kHeader) + R"GLSL(
layout(binding = 0) uniform sampler2D u_colour;
layout(binding = 1) uniform sampler2D u_depth;
layout(binding = 2) uniform sampler2D u_opaque_depth;
uniform int u_ss;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out float o_depth;
layout(location = 2) out float o_opaque_depth;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 c = vec3(0.0);
  float d = positive_infinity(), od = positive_infinity();
  for (int j = 0; j < u_ss; ++j)
    for (int i = 0; i < u_ss; ++i) {
      ivec2 t = p * u_ss + ivec2(i, j);
      c += texelFetch(u_colour, t, 0).rgb;
      d = min(d, texelFetch(u_depth, t, 0).r);
      od = min(od, texelFetch(u_opaque_depth, t, 0).r);
    }
  o_colour = vec4(c / float(u_ss * u_ss), 1.0);
  o_depth = d;
  o_opaque_depth = od;
}
)GLSL";
}

}  // namespace spume::shaders
