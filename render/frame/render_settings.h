#pragma once
// The render half of a scene (the "render" object), validated into plain values. Lengths in m,
// colours linear RGB. Every key is declared once, with its unit, default and range, in
// keys/render_keys.h (`spume keys render` lists them); radius defaults are multiples of the fluid
// particle radius r, so a scene with no render keys at all still renders something sensible.
#include <optional>
#include <string>
#include <vector>

#include "render/camera/camera.h"
#include "sim/core/params.h"
#include "render/gl/environment.h"
#include "render/surface/reconstruct.h"
#include "render/volume/volume_types.h"
#include "render/keys/render_keys.h"

namespace spume {

struct RenderSettings {
  int width = int(keys::render::resolution.value[0]), height = int(keys::render::resolution.value[1]);
  std::vector<CameraKey> camera;  // empty: frame the scene's bounds (auto_camera)
  Vec3f camera_up = Vec3f::UnitY();  // set by the caller from the scene's gravity
  bool draw_surface = keys::render::surface.value[0] != 0.0;
  bool draw_solids = keys::render::solids.value[0] != 0.0;
  int supersample = int(keys::render::supersample.value[0]);
  SurfaceParams surface;
  VolumeSettings volume;
  Environment environment;
  std::optional<float> ground_height;  // m; absent: just below the lowest solid or particle
  WaterLook water;
  std::string frame_pattern = keys::render::frames.choices;
  bool exr = keys::render::exr.value[0] != 0.0;  // also each frame's layers as OpenEXR (frame/frame_layers.h)

  // True when some diffuse type is drawn (else the diffuse stage and the volume pass are left out).
  bool draws_diffuse() const;
  // The EXR beside each PNG: frame_pattern with its extension .exr.
  std::string exr_pattern() const;
};

// `particle_radius` (m) sets the radius defaults.
RenderSettings read_render_settings(const ParamReader& render, float particle_radius);

// A camera key that frames `bounds` from an elevated three-quarter view, `up` being the scene's up.
CameraKey auto_camera(const Aabb& bounds, const Vec3f& up, float fov_y_degrees, float aspect);

}  // namespace spume
