#pragma once
// Sun shadows: a depth map of the solids seen along the sun direction (orthographic, fitted to the
// solids), filtered by one bilinear comparison tap (PCF) by the opaque and water shaders. Only solids cast shadows:
// the water is treated as clear (no caustics, no shadow).
#include <Eigen/Core>
#include <vector>

#include "core/vec.h"
#include "gl_objects.h"

namespace spume {

class SunShadow {
 public:
  static constexpr int kSize = 2048;  // texels per side

  struct Caster {
    const GpuMesh* mesh;
    Vec3f offset;  // m
    Aabb bounds;   // m, including the offset
  };

  SunShadow();  // needs a current context
  // Fits the sun's view around the casters and renders their depth; leaves the viewport and
  // framebuffer changed. Returns false when there is nothing to cast a shadow.
  bool render(const std::vector<Caster>& casters, const Vec3f& sun_direction);

  const Eigen::Matrix4f& view_proj() const { return view_proj_; }  // world -> sun clip space
  float texel_size() const { return texel_; }                      // m
  GLuint texture() const { return depth_.id(); }

 private:
  GlTexture depth_;
  GlFramebuffer fbo_;
  GlProgram program_;
  Eigen::Matrix4f view_proj_ = Eigen::Matrix4f::Identity();
  float texel_ = 0.0f;
};

// GLSL: the sampler (unit 3) and `float sun_visibility(vec3 world, vec3 normal)`, reading the Frame
// block's sun_view_proj and shadow fields.
const char* sun_shadow_glsl();

}  // namespace spume
