#pragma once
// Sun shadows: a depth map of the solids seen along the sun direction (orthographic, fitted to the
// solids), filtered by one bilinear comparison tap (PCF) by the opaque and water shaders. Only solids cast shadows:
// the water is treated as clear (no caustics, no shadow).
#include <Eigen/Core>
#include <vector>

#include "sim/core/vec.h"
#include "render/gl/gl_objects.h"

namespace spume {

class SunShadow {
 public:
  static constexpr int kSize = 2048;  // texels per side

  // How thick walls of no thickness (a tank's) are made in the shadow map, in texels. Such walls that
  // meet shade each other right up to the edge, where their depths from the sun become equal, and the
  // biases against acne (polygon offset 1.5 x the caster's depth slope, bilinear PCF reaching a texel
  // and a half, the receiver's normal offset) then read a strip along the edge as lit: a bright line.
  // As slabs of thickness t behind the walls, a receiver at distance d from the wall that shades it
  // (walls at right angles; theta between the sun and that wall's normal) lies (d + t) / cos(theta)
  // behind that slab's outer face along the sun's rays, and the biases amount to under 3 texels x
  // tan(theta) (1.5 from the offset, sqrt(2) from PCF and the texel-centre samples; the normal offset
  // runs parallel to the caster): in shadow for every d >= 0 and sun angle once t >= 3 texels x
  // sin(theta). 4 leaves a margin; the closed slab keeps the walls' own faces, so shadows cast over a
  // rim stay where the thin wall casts them.
  static constexpr float kWallTexels = 4.0f;

  struct Caster {
    const GpuMesh* mesh;
    Vec3f offset;            // m
    Aabb bounds;             // m, including the offset (the slabs before they are thickened)
    bool thickened = false;  // mesh is walls' slabs: each vertex moves by its normal x wall_thickness()
  };

  SunShadow();  // needs a current context
  // Fits the sun's view around the casters and renders their depth; leaves the viewport and
  // framebuffer changed. Returns false when there is nothing to cast a shadow.
  bool render(const std::vector<Caster>& casters, const Vec3f& sun_direction);

  const Eigen::Matrix4f& view_proj() const { return view_proj_; }  // world -> sun clip space
  float texel_size() const { return texel_; }                      // m
  float wall_thickness() const { return wall_; }                   // m, kWallTexels texels (thickened casters)
  GLuint texture() const { return depth_.id(); }

 private:
  GlTexture depth_;
  GlFramebuffer fbo_;
  GlProgram program_;
  Eigen::Matrix4f view_proj_ = Eigen::Matrix4f::Identity();
  float texel_ = 0.0f, wall_ = 0.0f;
};

// GLSL: the sampler (unit 3) and `float sun_visibility(vec3 world, vec3 normal)`, reading the Frame
// block's sun_view_proj and shadow fields.
const char* sun_shadow_glsl();

}  // namespace spume
