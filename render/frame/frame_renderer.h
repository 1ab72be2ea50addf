#pragma once
// One frame, from plain inputs to an 8-bit sRGB image: surface reconstruction of the fluid, the OSMesa
// pass (C_b), the Eq. 9 volume pass over the diffuse particles (L, C_d) and the composite
// C_p = (1 - L) C_d + L C_b. Only what the frame needs runs: no reconstruction when the surface is
// not drawn or there is no fluid, no GL context when nothing shows geometry, no volume pass when no
// drawn diffuse particle exists. The volume pass runs on a thread of its own beside the surface pass
// (one after the other with --threads 1). With RenderSettings::exr, the frame is also taken apart into
// the layers and motion vectors of its EXR (frame_layers.h, motion_vectors.h).
#include <optional>
#include <span>
#include <vector>

#include "render/camera/camera.h"
#include "render/frame/frame_layers.h"
#include "render/frame/motion_vectors.h"
#include "render/gl/surface_pass.h"
#include "render/image/image.h"
#include "render/frame/render_settings.h"
#include "render/surface/triangle_mesh.h"
#include "sim/geometry/solids.h"

namespace spume {

struct SolidMesh {
  TriangleMesh mesh;  // world space at this frame, m
  Vec3f albedo = Vec3f(0.55f, 0.55f, 0.55f);
  // Walls of no thickness (a tank's) cast the sun's shadow from this instead (SceneSolid::shadow_caster).
  // Empty: `mesh` casts it.
  TriangleMesh shadow_caster;
};

// The surface pass's view of a solid (pointing into `s`, which must outlive it).
SceneSolid scene_solid(const SolidMesh& s);

struct FrameInputs {
  int index = 0;
  double time = 0.0;                  // s: picks the camera key
  std::span<const Vec3f> fluid;       // fluid particle positions; empty: no surface
  const DiffusePoints* diffuse = nullptr;  // positions and types: all the volume pass reads
  std::span<const Vec3f> diffuse_velocities;  // m/s, for motion blur and motion vectors
  std::span<const Vec3f> fluid_velocities;    // m/s, for motion vectors; may be empty
  const SolidSet* solid_set = nullptr;         // the solids at `time` with their velocities; may be null
  std::vector<SolidMesh> solids;
};

// What ran for a frame, and how long it took (wall clock, s).
struct FrameReport {
  bool reconstructed = false, used_gl = false, volume = false;
  size_t triangles = 0, spheres = 0;
  double reconstruct_seconds = 0, surface_seconds = 0, volume_seconds = 0, composite_seconds = 0;
  double layers_seconds = 0;  // taking the frame apart for its EXR (RenderSettings::exr)
  SurfacePassStats surface;  // the surface pass by stage
};

// The PNG's image and, with RenderSettings::exr, the frame's layers.
struct RenderedFrame {
  ImageRGB8 image;
  std::optional<FrameLayers> layers;
};

class FrameRenderer {
 public:
  explicit FrameRenderer(RenderSettings settings);
  // Call from one thread (the OSMesa context is the calling thread's); each stage is parallel inside.
  ImageRGB8 render(const FrameInputs& inputs, FrameReport* report = nullptr) { return render_frame(inputs, report).image; }
  RenderedFrame render_frame(const FrameInputs& inputs, FrameReport* report = nullptr);
  const RenderSettings& settings() const { return settings_; }
  Camera camera_at_time(double time) const;

 private:
  MotionScene motion_scene(const FrameInputs& in, const Camera& camera) const;  // for the EXR's motion vectors

  RenderSettings settings_;
  SurfacePass surface_pass_;
};

}  // namespace spume
