#include "render/pipeline/frame_renderer.h"


#include "sim/core/error.h"
#include "sim/core/stopwatch.h"
#include "render/surface/reconstruct.h"
#include "render/volume/composite.h"
#include "render/volume/volume_pass.h"

namespace spume {
namespace {

SurfacePassOptions pass_options(const RenderSettings& s) {
  SurfacePassOptions o;
  o.supersample = s.supersample;
  return o;
}

}  // namespace

SceneSolid scene_solid(const SolidMesh& s) {
  return SceneSolid{&s.mesh, s.albedo, Vec3f::Zero(), s.shadow_caster.empty() ? nullptr : &s.shadow_caster};
}

FrameRenderer::FrameRenderer(RenderSettings settings)
    : settings_(std::move(settings)), surface_pass_(pass_options(settings_)) {
  if (settings_.camera.empty()) fail("render: no camera (the caller frames the scene when the scene has none)");
}

Camera FrameRenderer::camera_at_time(double time) const {
  Camera camera = camera_at(settings_.camera, time, settings_.width, settings_.height);
  camera.up = settings_.camera_up;
  return camera;
}

ImageRGB8 FrameRenderer::render(const FrameInputs& in, FrameReport* report) {
  FrameReport r;
  const Camera camera = camera_at_time(in.time);

  TriangleMesh water;
  if (settings_.draw_surface && !in.fluid.empty()) {
    const Stopwatch t0;
    water = reconstruct_surface(in.fluid, settings_.surface);
    r.reconstructed = true;
    r.triangles = water.triangle_count();
    r.reconstruct_seconds = t0.seconds();
  }

  SurfaceScene scene;
  scene.fluid = water.empty() ? nullptr : &water;
  scene.environment = settings_.environment;
  scene.water = settings_.water;
  TriangleMesh opaque;
  for (const SolidMesh& s : in.solids) {
    scene.solids.push_back(scene_solid(s));
    opaque.append(s.mesh);
  }
  Stopwatch t0;
  SurfacePassStats surface_stats;
  const SurfaceImage background = surface_pass_.render(scene, camera, &surface_stats);
  r.used_gl = surface_stats.used_gl;
  r.surface = surface_stats;
  r.surface_seconds = t0.seconds();

  ImageRGBf colour = background.colour;
  if (in.diffuse && volume_pass_needed(*in.diffuse, settings_.volume)) {
    t0.restart();
    VolumeSurfaces surfaces;
    surfaces.water = water.empty() ? nullptr : &water;
    surfaces.solids = opaque.empty() ? nullptr : &opaque;
    VolumeStats volume_stats;
    const VolumeImage volume = render_volume(*in.diffuse, camera, settings_.volume, surfaces, &volume_stats);
    r.volume = true;
    r.spheres = volume_stats.spheres;
    r.volume_seconds = t0.seconds();
    t0.restart();
    colour = composite(volume, background.colour);
    r.composite_seconds = t0.seconds();
  }
  if (report) *report = r;
  return to_srgb8(colour);
}

}  // namespace spume
