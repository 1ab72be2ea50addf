#include "render/gl/sun_shadow.h"

#include <algorithm>
#include <cmath>

#include "render/gl/osmesa_context.h"

namespace spume {
namespace {

const char* kVertex = R"GLSL(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_sun;
uniform vec3 u_offset;
uniform float u_thickness;  // m: walls' slabs (their normals say where each vertex moves); 0 otherwise
void main() { gl_Position = u_sun * vec4(a_position + u_offset + u_thickness * a_normal, 1.0); }
)GLSL";

const char* kFragment = R"GLSL(#version 450 core
void main() {}
)GLSL";

}  // namespace

SunShadow::SunShadow() : depth_(GL_DEPTH_COMPONENT32F, kSize, kSize), program_(kVertex, kFragment, "sun shadow") {
  // Hardware PCF: comparison sampling with bilinear weights.
  glBindTexture(GL_TEXTURE_2D, depth_.id());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glBindTexture(GL_TEXTURE_2D, 0);
  fbo_ = GlFramebuffer({}, depth_.id(), "sun shadow");
  check_gl("creating the sun shadow map");
}

bool SunShadow::render(const std::vector<Caster>& casters, const Vec3f& sun_direction) {
  if (casters.empty()) return false;
  // Sun basis: `back` points towards the sun; distance from the sun grows along -back.
  const Vec3f back = sun_direction.normalized();
  const Vec3f hint = std::abs(back.y()) < 0.99f ? Vec3f::UnitY() : Vec3f::UnitX();
  const Vec3f right = hint.cross(back).normalized(), up = back.cross(right);
  // Fitted around the casters' bounds in the sun's frame, thickened casters' grown by the thickness.
  auto fit = [&](float thickness) {
    Vec3f lo = Vec3f::Constant(INFINITY), hi = Vec3f::Constant(-INFINITY);
    for (const Caster& c : casters) {
      const Vec3f grow = Vec3f::Constant(c.thickened ? thickness : 0.0f);
      const Vec3f bmin = c.bounds.min - grow, bmax = c.bounds.max + grow;
      for (int k = 0; k < 8; ++k) {
        const Vec3f p(k & 1 ? bmax.x() : bmin.x(), k & 2 ? bmax.y() : bmin.y(), k & 4 ? bmax.z() : bmin.z());
        const Vec3f q(right.dot(p), up.dot(p), -back.dot(p));
        lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
      }
    }
    // Square texels; a small border so PCF taps at the edge stay inside.
    const float half = 0.5f * std::max(hi.x() - lo.x(), hi.y() - lo.y()) * (1.0f + 4.0f / kSize) + 1e-4f;
    const Vec3f mid = 0.5f * (lo + hi);
    const float depth_half = 0.5f * (hi.z() - lo.z()) * 1.02f + 1e-4f;
    Eigen::Matrix4f m = Eigen::Matrix4f::Zero();
    m.block<1, 3>(0, 0) = right.transpose() / half;
    m.block<1, 3>(1, 0) = up.transpose() / half;
    m.block<1, 3>(2, 0) = -back.transpose() / depth_half;
    m(0, 3) = -mid.x() / half, m(1, 3) = -mid.y() / half, m(2, 3) = -mid.z() / depth_half, m(3, 3) = 1.0f;
    view_proj_ = m;
    texel_ = 2.0f * half / kSize;
  };
  fit(0.0f);
  wall_ = 0.0f;
  if (std::any_of(casters.begin(), casters.end(), [](const Caster& c) { return c.thickened; })) {
    // The thickness from the texel of the map without it; fitting the map around the thickened walls
    // widens a texel by at most 2 sqrt(3) kWallTexels / kSize (0.7%): still over 3.9 texels.
    wall_ = kWallTexels * texel_;
    fit(wall_);
  }

  fbo_.bind();
  glViewport(0, 0, kSize, kSize);
  glDepthMask(GL_TRUE);
  const float one = 1.0f;
  glClearBufferfv(GL_DEPTH, 0, &one);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5f, 2.0f);  // slope-scaled bias against self-shadowing acne
  program_.use();
  glUniformMatrix4fv(glGetUniformLocation(program_.id(), "u_sun"), 1, GL_FALSE, view_proj_.data());
  const GLint offset = glGetUniformLocation(program_.id(), "u_offset"),
              thickness = glGetUniformLocation(program_.id(), "u_thickness");
  for (const Caster& c : casters) {
    glUniform3f(offset, c.offset.x(), c.offset.y(), c.offset.z());
    glUniform1f(thickness, c.thickened ? wall_ : 0.0f);
    c.mesh->draw();
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
  check_gl("rendering the sun shadow map");
  return true;
}

const char* sun_shadow_glsl() {
  return R"GLSL(
layout(binding = 3) uniform sampler2DShadow u_shadow;
float sun_visibility(vec3 world, vec3 n) {
  if (shadow.x < 0.5) return 1.0;
  vec4 c = sun_view_proj * vec4(world + n * (1.5 * shadow.w), 1.0);  // normal offset: no acne
  vec3 q = c.xyz * 0.5 + 0.5;
  if (any(lessThan(q.xy, vec2(0.0))) || any(greaterThan(q.xy, vec2(1.0)))) return 1.0;
  float ref = min(q.z, 1.0);  // receivers beyond the casters' far side stay comparable
  // One bilinear comparison tap (hardware PCF over 2x2 texels). A texel is about a pixel or less at the
  // scenes' framings; four taps (a 3x3 tent) cost 4x as much on llvmpipe for edges barely softer.
  return texture(u_shadow, vec3(q.xy, ref));
}
)GLSL";
}

}  // namespace spume
