#pragma once
// The render half of a scene (the "render" object), validated into plain values. Lengths in m,
// colours linear RGB. Defaults are relative to the fluid particle radius r, so a scene with no render
// keys at all still renders something sensible.
//
//   "render": {
//     "resolution": [960, 540],           // pixels
//     "spp": 1,                           // eye rays per pixel (jittered, deterministic)
//     "seed": 0,                          // jitter key, with the frame number
//     "camera": {"position": [..], "target": [..], "fov": 45}       // or "keys": [{"time": s, ...}]
//                                         // absent: framed on the scene's bounds
//     "surface": true,                    // draw the fluid surface (reconstruction + OSMesa)
//     "surface_cell": 1,                  // marching-cubes cell in units of r
//     "surface_smoothing": 8,             // Taubin iterations on the surface mesh (0: off)
//     "solids": true,                     // draw the scene's solids
//     "supersample": 1,                   // OSMesa pass per-axis supersampling
//     "integrator": "exact",              // "exact" (union-of-spheres length) or "march" (Eq. 9 as written)
//     "march_step": 0,                    // m, Delta x of "march"; 0: half the smallest drawn radius
//     "alpha": 50,                        // 1/m, Eq. 9's absorption scale
//     "spray":  {"radius": 0.3 r, "color": [0.92, 0.95, 1.0]},  // radius 0: not drawn
//     "foam":   {"radius": 0.5 r, "color": [0.95, 0.95, 0.95]},
//     "bubble": {"radius": 0.4 r, "color": [0.80, 0.90, 1.00]},
//     "water": {"absorption": [3.5, 1.1, 0.75], "ior": 1.333, "roughness": 0.04,   // 1/m: both passes
//               "refraction": 1, "scene_reflections": true},
//     "ground": true, "ground_height": (just below everything),
//     "frames": "frames/%04d.png"         // output pattern under OUT/<scene>/ (%04d, %d or ####)
//   }
#include <optional>
#include <string>
#include <vector>

#include "camera/camera.h"
#include "core/params.h"
#include "gl/environment.h"
#include "surface/reconstruct.h"
#include "volume/volume_types.h"

namespace spume {

struct RenderSettings {
  int width = 960, height = 540;
  std::vector<CameraKey> camera;  // empty: frame the scene's bounds (auto_camera)
  Vec3f camera_up = Vec3f::UnitY();  // set by the caller from the scene's gravity
  bool draw_surface = true;
  bool draw_solids = true;
  int supersample = 1;
  SurfaceParams surface;
  VolumeSettings volume;
  Environment environment;
  std::optional<float> ground_height;  // m; absent: just below the lowest solid or particle
  WaterLook water;
  std::string frame_pattern = "frames/%04d.png";

  // True when some diffuse type is drawn (else the diffuse stage and the volume pass are left out).
  bool draws_diffuse() const;
};

// `particle_radius` (m) sets the radius defaults.
RenderSettings read_render_settings(const ParamReader& render, float particle_radius);

// A camera key that frames `bounds` from an elevated three-quarter view, `up` being the scene's up.
CameraKey auto_camera(const Aabb& bounds, const Vec3f& up, float fov_y_degrees, float aspect);

}  // namespace spume
