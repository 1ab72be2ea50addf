#include "render/gl/surface_shaders.h"

#include "render/gl/environment.h"
#include "render/gl/sun_shadow.h"

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

}  // namespace

std::string frame_block_glsl() { return kHeader; }
std::string fragment_header() { return frame_block_glsl() + environment_glsl() + sun_shadow_glsl(); }

std::string sky_vertex() {
  return frame_block_glsl() + R"GLSL(
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
  return frame_block_glsl() + R"GLSL(
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

std::string solid_fragment() {
  return fragment_header() + R"GLSL(
in vec3 v_world;
in vec3 v_normal;
in float v_depth;
uniform vec3 u_albedo;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out float o_depth;
void main() {
  vec3 n = normalize(v_normal);
  if (dot(n, eye.xyz - v_world) < 0.0) n = -n;  // two-sided: a tank is seen from inside
  o_colour = vec4(u_albedo * env_irradiance(n, sun_visibility(v_world, n)) / PI, 1.0);
  o_depth = v_depth;
}
)GLSL";
}

std::string ground_fragment() {
  return fragment_header() + R"GLSL(
in vec3 v_world;
in float v_depth;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out float o_depth;
void main() {
  o_colour = vec4(env_ground(v_world, eye.xyz, sun_visibility(v_world, vec3(0.0, 1.0, 0.0))), 1.0);
  o_depth = v_depth;
}
)GLSL";
}

std::string depth_only_fragment() {
  return frame_block_glsl() + R"GLSL(
void main() {}
)GLSL";
}

std::string downsample_fragment() {
  return frame_block_glsl() + R"GLSL(
layout(binding = 0) uniform sampler2D u_colour;
layout(binding = 1) uniform sampler2D u_depth;
layout(binding = 2) uniform sampler2D u_opaque_depth;
layout(binding = 3) uniform sampler2D u_opaque_colour;
uniform int u_ss;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out float o_depth;
layout(location = 2) out float o_opaque_depth;
layout(location = 3) out vec4 o_opaque_colour;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 c = vec3(0.0), oc = vec3(0.0);
  float d = positive_infinity(), od = positive_infinity();
  for (int j = 0; j < u_ss; ++j)
    for (int i = 0; i < u_ss; ++i) {
      ivec2 t = p * u_ss + ivec2(i, j);
      c += texelFetch(u_colour, t, 0).rgb;
      oc += texelFetch(u_opaque_colour, t, 0).rgb;
      d = min(d, texelFetch(u_depth, t, 0).r);
      od = min(od, texelFetch(u_opaque_depth, t, 0).r);
    }
  o_colour = vec4(c / float(u_ss * u_ss), 1.0);
  o_opaque_colour = vec4(oc / float(u_ss * u_ss), 1.0);
  o_depth = d;
  o_opaque_depth = od;
}
)GLSL";
}

}  // namespace spume::shaders
