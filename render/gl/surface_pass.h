#pragma once
// The surface pass: sky, ground, the scene's solids and the fluid surface drawn as water, off-screen
// with OSMesa, into the background C_b that the volume pass composites over (Eq. 9) and the depths at
// which its march stops.
//
// Passes (float render targets, so C_b keeps full precision and values above 1):
//  0. sun shadow map of the solids (sun_shadow.h)
//  1. opaque: solids (diffuse, shadowed), ground plane, analytic sky  -> colour, linear depth
//  2. water back faces                                                -> depth buffer (where rays leave water)
//  3. water front faces over a copy of pass 1                         -> normal, linear depth, stencil
//  4. water shading, once per pixel the stencil marks: Schlick-Fresnel reflection of the sky and, in
//     screen space, of pass 1's image; refraction of pass 1's image absorbed per channel over the
//     path through the water (Beer-Lambert) plus an in-scattered deep colour; GGX sun highlight
//     (shadowed). See water_shader.cpp.
//  5. down-sample (supersampling only) and read the float targets back.
// The steps are in surface_gpu.h, the targets in surface_targets.h, the frame's camera and matrices in
// surface_view.h.
// Colour is LINEAR RGB (the image writer encodes sRGB). Assumes the camera is above the water and the
// ground. Water is treated as clear for shadows (no caustics, no shadow cast by water).
#include <memory>
#include <vector>

#include "render/camera/camera.h"
#include "render/gl/environment.h"
#include "render/image/image.h"
#include "render/gl/osmesa_context.h"
#include "render/surface/triangle_mesh.h"

namespace spume {

struct SceneSolid {
  const TriangleMesh* mesh = nullptr;         // drawn two-sided (a tank is seen from inside)
  Vec3f albedo = Vec3f(0.55f, 0.55f, 0.55f);  // linear diffuse reflectance
  Vec3f offset = Vec3f::Zero();               // m, translation at this frame (kinematic solids)
  // For walls of no thickness: what casts the sun's shadow instead of `mesh`, thickened in the shadow
  // map (a wall that shades the wall it meets would otherwise let light leak along their edge; see
  // SunShadow::kWallTexels): each vertex moves by its normal times a few texels; zero normals stay.
  // Null: `mesh` casts the shadow as it is (closed solids).
  const TriangleMesh* shadow_caster = nullptr;
};

struct SurfaceScene {
  const TriangleMesh* fluid = nullptr;  // the reconstructed surface (closed, wound outward); may be null
  std::vector<SceneSolid> solids;
  Environment environment;
  WaterLook water;

  bool shows_water() const;  // a fluid surface with triangles
  // A GL context is needed only when there is a surface or a solid to draw.
  bool shows_geometry() const;
};

struct SurfaceImage {
  ImageRGBf colour;                 // linear RGB, top row first (values may exceed 1: the sun)
  std::vector<float> depth;         // m along the view axis to the nearest thing drawn, water included; +inf: sky
  std::vector<float> opaque_depth;  // the same ignoring the water: where the diffuse march must stop
  ImageRGBf opaque_colour;          // SurfacePassOptions::opaque_colour only: pass 1, what lies under the water
};

struct SurfacePassOptions {
  // Render at this factor per axis and box-filter down (anti-aliasing; depths take the nearest sample).
  // 1 by default: 2 costs 2.5-3x the time on llvmpipe (960x540, wave frames 48-52: 0.09 s at 1, 0.24 s at 2).
  int supersample = 1;
  bool opaque_colour = false;  // also read back pass 1's image (the EXR frames' layers)
  OsmesaOptions gl;
};

struct SurfacePassStats {
  bool used_gl = false;
  size_t triangles = 0;
  double seconds = 0.0;  // all of render()
  // Stages, GL work finished at each boundary: creating the context and compiling the programs (the
  // first frame with geometry only), mesh uploads, the sun shadow map, sky/ground/solids, the water's
  // back faces, its front faces, down-sampling (supersampling only), read-back.
  double seconds_context = 0.0, seconds_upload = 0.0, seconds_shadow = 0.0, seconds_opaque = 0.0;
  double seconds_water_back = 0.0, seconds_water_front = 0.0, seconds_resolve = 0.0, seconds_readback = 0.0;
};

class SurfacePass {
 public:
  explicit SurfacePass(const SurfacePassOptions& options = {});
  ~SurfacePass();
  SurfacePass(const SurfacePass&) = delete;
  SurfacePass& operator=(const SurfacePass&) = delete;

  // Creates the OSMesa context on the first call that shows geometry and keeps it for later frames;
  // frames without geometry get the sky and ground from the CPU (render_background). Call from one
  // thread. Throws Error on GL failures.
  SurfaceImage render(const SurfaceScene& scene, const Camera& camera, SurfacePassStats* stats = nullptr);
  bool has_context() const { return gpu_ != nullptr; }

 private:
  struct Gpu;  // the GL state kept between frames and the passes' steps (surface_gpu.h)
  // The frame drawn with GL: creates the context on first use, then passes 0-5 (above).
  SurfaceImage render_gl(const SurfaceScene& scene, const Camera& camera, SurfacePassStats& stats);

  SurfacePassOptions options_;
  std::unique_ptr<Gpu> gpu_;
};

// Sky and ground only, on the CPU (the same model as the GL pass, to float rounding).
SurfaceImage render_background(const Environment& environment, const Camera& camera);

// Half-size (m) of the ground quad around the camera: far enough that haze hides its edge.
float ground_extent(const Environment& environment);

}  // namespace spume
