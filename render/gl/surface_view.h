#pragma once
// The camera of one surface-pass frame: the supersampled size, near and far planes fitted around
// what is drawn, the projection drawn upside down, and the shaders' Frame block made from them.
#include <Eigen/Core>

#include "render/camera/camera.h"
#include "render/gl/sun_shadow.h"
#include "render/gl/surface_pass.h"
#include "render/gl/surface_shaders.h"

namespace spume {

struct SurfaceView {
  Camera camera;                // the frame's camera at the supersampled size
  float near_d = 0.0f, far_d = 0.0f;  // m, the clip planes
  // Drawn upside down (y negated in clip space, so the winding flips too): GL's bottom-up rows then
  // read back in the image's top-first order.
  Eigen::Matrix4f proj, view, view_proj;
};

// The view of `camera` (sized as the output) rendered at `supersample` times its size per axis.
SurfaceView surface_view(const SurfaceScene& scene, const Camera& camera, int supersample);

// The Frame block: the view's matrices, eye, planes and viewport, and the sun's shadow map
// (`shadows`: whether it holds any caster).
shaders::FrameBlock frame_block(const SurfaceView& view, const SunShadow& shadow, bool shadows);

}  // namespace spume
