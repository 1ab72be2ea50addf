// The water surface's fragment shader (declared in surface_shaders.h): Schlick-Fresnel reflection of the
// sky and, in screen space, of the opaque scene; refraction of the opaque scene behind and under the
// water, absorbed over the path the refracted ray takes through it (Beer-Lambert per channel) plus an
// in-scattered deep colour; a GGX sun highlight. Deferred: the water's front faces write only their
// normal and depth, and one full-screen pass shades each water pixel once. llvmpipe shades whole 4x4
// blocks, so shading the marching-cubes triangles (a few pixels each) directly would run the costly
// shader on several times as many pixels as it colours.
#include "render/gl/surface_shaders.h"

namespace spume::shaders {

std::string water_normal_fragment() {
  return frame_block_glsl() + R"GLSL(
in vec3 v_normal;
in float v_depth;
layout(location = 0) out vec4 o_normal;
layout(location = 1) out float o_depth;
void main() {
  o_normal = vec4(normalize(v_normal) * 0.5 + 0.5, 0.0);  // unsigned 10-bit target
  o_depth = v_depth;
}
)GLSL";
}

std::string water_fragment() {
  return fragment_header() + R"GLSL(
in vec2 v_ndc;
layout(binding = 0) uniform sampler2D u_behind_colour;  // opaque scene and sky, linear RGB
layout(binding = 1) uniform sampler2D u_behind_depth;   // its linear depth
layout(binding = 2) uniform sampler2D u_back_z;         // window depth of the water's back faces
layout(binding = 4) uniform sampler2D u_water_normal;   // the nearest front face's normal
layout(binding = 5) uniform sampler2D u_water_depth;    // and its linear depth
layout(location = 0) out vec4 o_colour;

ivec2 texel(vec2 uv) { return clamp(ivec2(uv * viewport.xy), ivec2(0), ivec2(viewport.xy) - 1); }
// Linear depth (m) from window depth d of the perspective projection (proj.z, proj.w: near, far); the
// far plane, where nothing was drawn, is infinitely far.
float linear_depth(float d) {
  float n = proj.z, f = proj.w;
  return d >= 1.0 ? positive_infinity() : 2.0 * n * f / (f + n - (2.0 * d - 1.0) * (f - n));
}
// Where the view ray through this texel leaves the water: its back face or the opaque scene.
float exit_depth(ivec2 t) {
  return min(texelFetch(u_behind_depth, t, 0).r, linear_depth(texelFetch(u_back_z, t, 0).r));
}
vec3 world_at(vec2 uv, float depth) {
  vec2 ndc = uv * 2.0 - 1.0;
  return (inv_view * vec4(ndc.x / proj.x * depth, ndc.y / proj.y * depth, -depth, 1.0)).xyz;
}
// Screen position (uv) and view depth of a point given in clip space (depth <= 0: behind the camera).
vec3 screen(vec4 c) { return vec3(c.xy / c.w * 0.5 + 0.5, c.w); }
bool on_screen(vec3 s) { return s.z > 0.0 && all(greaterThanEqual(s.xy, vec2(0.0))) && all(lessThan(s.xy, vec2(1.0))); }

// Where the ray c0 + dc t (clip space) leaves the view frustum (its sides, the near and the far plane).
float frustum_exit(vec4 c0, vec4 dc) {
  // Each side is g0 + g1 t >= 0, true at t = 0; the ray leaves it at -g0 / g1 when g1 < 0.
  vec4 g0 = vec4(c0.w - c0.x, c0.w + c0.x, c0.w - c0.y, c0.w + c0.y);
  vec4 g1 = vec4(dc.w - dc.x, dc.w + dc.x, dc.w - dc.y, dc.w + dc.y);
  float t = dc.w > 0.0 ? (proj.w - c0.w) / dc.w : (dc.w < 0.0 ? (proj.z - c0.w) / dc.w : 1e30);
  for (int i = 0; i < 4; ++i)
    if (g1[i] < 0.0) t = min(t, -g0[i] / g1[i]);
  return max(t, 0.0);
}

// Screen-space reflection of the opaque scene along R from P: steps growing geometrically from `first`
// to where the ray leaves the screen (perspective shrinks distant steps on screen alike), until one
// ends behind the opaque surface, then bisection of that step. The hit counts when the refined point
// lies within `thickness` behind that surface: farther, the ray passed behind something nearer (an
// edge of a solid) rather than meeting it. Returns the colour found and its weight: 0 without a hit
// or off the screen, fading out near the screen's edge so reflections do not end at a hard line.
const int kMarchSteps = 10, kBisections = 5;
vec4 scene_reflection(vec3 P, vec3 R, float first) {
  // Clip coordinates are linear along the ray: one matrix product for the whole march.
  vec4 c0 = view_proj * vec4(P, 1.0), dc = view_proj * vec4(R, 0.0);
  float reach = frustum_exit(c0, dc);
  if (reach <= first) return vec4(0.0);
  float growth = pow(reach / first, 1.0 / float(kMarchSteps - 1));
  float t_in_front = 0.0, t = first;
  bool behind = false;
  for (int k = 0; k < kMarchSteps; ++k) {
    vec3 s = screen(c0 + dc * t);
    if (!on_screen(s)) break;
    if (s.z >= texelFetch(u_behind_depth, texel(s.xy), 0).r) {
      behind = true;
      break;
    }
    t_in_front = t, t *= growth;
  }
  if (!behind) return vec4(0.0);
  float lo = t_in_front, hi = t;
  for (int k = 0; k < kBisections; ++k) {
    float mid = 0.5 * (lo + hi);
    vec3 s = screen(c0 + dc * mid);
    if (s.z >= texelFetch(u_behind_depth, texel(s.xy), 0).r) hi = mid; else lo = mid;
  }
  vec3 s = screen(c0 + dc * hi);
  float thickness = 0.05 * hi + 2.0 * first;
  if (s.z - texelFetch(u_behind_depth, texel(s.xy), 0).r > thickness) return vec4(0.0);
  vec2 edge = abs(s.xy * 2.0 - 1.0);
  return vec4(texelFetch(u_behind_colour, texel(s.xy), 0).rgb, 1.0 - smoothstep(0.9, 1.0, max(edge.x, edge.y)));
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);
  vec2 uv = gl_FragCoord.xy * viewport.zw;
  float depth = texelFetch(u_water_depth, pixel, 0).r;
  vec3 P = world_at(uv, depth);
  vec3 V = normalize(eye.xyz - P);
  vec3 N = normalize(texelFetch(u_water_normal, pixel, 0).xyz * 2.0 - 1.0);
  // Smooth normals can face away near silhouettes: bend them back just enough.
  float ndv_raw = dot(N, V);
  if (ndv_raw < 0.02) N = normalize(N + (0.02 - ndv_raw) * V);
  float ndv = clamp(dot(N, V), 0.0, 1.0);
  float ior = water_abs.w;
  float f0 = (ior - 1.0) * (ior - 1.0) / ((ior + 1.0) * (ior + 1.0));
  float fresnel = f0 + (1.0 - f0) * pow(1.0 - ndv, 5.0);

  // Transmission: follow the refracted ray for the water thickness seen along the view ray, look up
  // the opaque scene where it lands, and absorb along the path (Beer-Lambert per channel).
  float ray_scale = length(eye.xyz - P) / depth;  // path length per unit of view depth
  float straight = max(exit_depth(texel(uv)) - depth, 0.0) * ray_scale;
  straight = min(straight, 1000.0);
  // Refracted path to the same depth below the surface (exact for a bottom parallel to the surface,
  // e.g. a tank floor under calm water): straight * cos(incidence) / cos(refraction).
  vec3 T = refract(-V, N, 1.0 / ior);
  float bent_length = straight * ndv / max(-dot(T, N), 1e-3);
  vec3 target = mix(P - V * straight, P + T * bent_length, water_params.x);
  vec4 clip = view_proj * vec4(target, 1.0);
  vec2 uv_r = clip.w > 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : uv;
  float exit_r = exit_depth(texel(uv_r));
  if (exit_r <= depth) {  // something in front of the water there: look straight through
    uv_r = uv;
    exit_r = exit_depth(texel(uv));
  }
  float path = isinf(exit_r) ? 1000.0 : min(distance(P, world_at(uv_r, exit_r)), 1000.0);
  vec3 transmittance = exp(-water_abs.rgb * path);
  vec3 behind = texelFetch(u_behind_colour, texel(uv_r), 0).rgb;
  vec3 transmitted = behind * transmittance + water_deep.rgb * (1.0 - transmittance);

  // Reflection: the opaque scene where the screen holds it, else the analytic sky (the sun disc comes
  // from the highlight below instead).
  vec3 R = reflect(-V, N);
  vec3 reflected = env_sky(R, false);
  if (water_params.y > 0.5) {
    float footprint = 2.0 * depth / (abs(proj.y) * viewport.y);  // m covered by a pixel at this depth
    vec4 hit = scene_reflection(P, R, 2.0 * footprint);
    reflected = mix(reflected, hit.rgb, hit.a);
  }

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
    highlight = sun_irr.rgb * D * G * Fh / (4.0 * max(ndv, 1e-3)) * sun_visibility(P, N);
  }
  o_colour = vec4(fresnel * reflected + (1.0 - fresnel) * transmitted + highlight, 1.0);
}
)GLSL";
}

}  // namespace spume::shaders
