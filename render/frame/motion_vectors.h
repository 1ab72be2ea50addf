#pragma once
// Screen-space motion vectors of a frame (the EXR's forward.u/v and backward.u/v), in pixels per frame,
// u to the right and v up (Nuke's convention): where the point a pixel shows will be one frame later
// (forward) and was one frame earlier (backward), moving at its velocity now while the camera moves
// along its keys.
//
// What a pixel shows moves with:
//   - the water: the fluid particles' velocities near the surface point (a weighted mean over those
//     within h = 2.5 r, weight (1 - d^2/h^2)^3);
//   - a solid: its rigid motion at the point (Solid::velocity_at of the solid nearest the point);
//   - the ground and the sky: nothing (only the camera moves them);
//   - diffuse material in front: the particles along the pixel's ray, each weighted by its chord, the
//     mix taking the material's opacity 1 - L against what lies behind (a transparent layer has no
//     single motion; this is the weighted compromise compositing tools expect).
#include <span>
#include <vector>

#include "render/camera/camera.h"
#include "render/frame/frame_layers.h"
#include "render/gl/surface_pass.h"
#include "render/volume/volume_types.h"
#include "sim/geometry/solids.h"

namespace spume {

struct MotionScene {
  Camera previous, now, next;  // at t - dt, t, t + dt
  double frame_seconds = 0.0;  // dt
  std::span<const Vec3f> fluid_positions, fluid_velocities;  // velocities may be empty: the water is still
  float fluid_support = 0.0f;                                  // m, h: particles within it count
  const SolidSet* solids = nullptr;                            // at t, with their velocities; may be null
  const DiffusePoints* diffuse = nullptr;                      // may be null
  std::span<const Vec3f> diffuse_velocities;
  std::array<float, kDiffuseTypeCount> radius{};               // drawn radii (0: not drawn)
};

// One {forward u, forward v, backward u, backward v} per pixel, rows top to bottom. `surface` gives
// the depths, `volume` (may be null) the diffuse opacity.
std::vector<Rgba> motion_vectors(const MotionScene& scene, const SurfaceImage& surface, const VolumeImage* volume);

}  // namespace spume
