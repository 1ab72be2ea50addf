#include "render/frame/frame_renderer.h"


#include <future>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/core/stopwatch.h"
#include "render/surface/reconstruct.h"
#include "render/volume/composite.h"
#include "render/volume/volume_pass.h"

namespace spume {
namespace {

SurfacePassOptions pass_options(const RenderSettings& s) {
  SurfacePassOptions o;
  o.supersample = s.supersample;
  o.opaque_colour = s.exr;  // the EXR's opaque and sky layers
  return o;
}

}  // namespace

SceneSolid scene_solid(const SolidMesh& s) {
  return SceneSolid{&s.mesh, s.albedo, Vec3f::Zero(), s.shadow_caster.empty() ? nullptr : &s.shadow_caster};
}

FrameRenderer::FrameRenderer(RenderSettings settings)
    : settings_(std::move(settings)), surface_pass_(pass_options(settings_)) {
  settings_.volume.split_types = settings_.exr;
  if (settings_.camera.empty()) fail("render: no camera (the caller frames the scene when the scene has none)");
}

Camera FrameRenderer::camera_at_time(double time) const {
  Camera camera = camera_at(settings_.camera, time, settings_.width, settings_.height);
  camera.up = settings_.camera_up;
  return camera;
}

MotionScene FrameRenderer::motion_scene(const FrameInputs& in, const Camera& camera) const {
  MotionScene m;
  // The scene's frame interval; a caller that sets none (a test, a single frame) gets 25 fps's.
  const double dt = settings_.volume.frame_seconds > 0.0 ? settings_.volume.frame_seconds : 1.0 / 25.0;
  m.previous = camera_at_time(in.time - dt), m.now = camera, m.next = camera_at_time(in.time + dt);
  m.frame_seconds = dt;
  m.fluid_positions = in.fluid, m.fluid_velocities = in.fluid_velocities;
  // 2.5 r: the few particles nearest a surface point (~8), a quarter of the kernel's neighbours to visit.
  m.fluid_support = 2.5f * settings_.surface.particle_radius;
  m.solids = in.solid_set;
  m.diffuse = in.diffuse, m.diffuse_velocities = in.diffuse_velocities;
  for (int k = 0; k < kDiffuseTypeCount; ++k) m.radius[size_t(k)] = settings_.volume.look[size_t(k)].radius;
  return m;
}

RenderedFrame FrameRenderer::render_frame(const FrameInputs& in, FrameReport* report) {
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
  // The volume pass needs only the meshes, so it runs beside the surface pass, which must stay on
  // this thread (its OpenGL context's) and leaves part of the processors idle.
  const bool volume_needed = in.diffuse && volume_pass_needed(*in.diffuse, settings_.volume);
  VolumeSurfaces surfaces;
  surfaces.water = water.empty() ? nullptr : &water;
  surfaces.solids = opaque.empty() ? nullptr : &opaque;
  VolumeStats volume_stats;
  auto volume_pass = [&] {
    const Stopwatch watch;
    VolumeImage volume =
        render_volume(*in.diffuse, camera, settings_.volume, surfaces, &volume_stats, in.diffuse_velocities);
    r.volume_seconds = watch.seconds();
    return volume;
  };
  std::future<VolumeImage> volume;
  if (volume_needed && thread_count() > 1) volume = std::async(std::launch::async, volume_pass);

  Stopwatch t0;
  SurfacePassStats surface_stats;
  const SurfaceImage background = surface_pass_.render(scene, camera, &surface_stats);
  r.used_gl = surface_stats.used_gl;
  r.surface = surface_stats;
  r.surface_seconds = t0.seconds();

  ImageRGBf colour = background.colour;
  std::optional<VolumeImage> diffuse;
  if (volume_needed) {
    diffuse = volume.valid() ? volume.get() : volume_pass();
    r.volume = true;
    r.spheres = volume_stats.spheres;
    t0.restart();
    colour = composite(*diffuse, background.colour);
    r.composite_seconds = t0.seconds();
  }
  RenderedFrame out;
  if (settings_.exr) {
    t0.restart();
    std::array<bool, kDiffuseTypeCount> drawn{};
    for (int k = 0; k < kDiffuseTypeCount; ++k) drawn[size_t(k)] = settings_.volume.drawn(DiffuseType(k));
    out.layers = frame_layers(colour, background, diffuse ? &*diffuse : nullptr, drawn, camera);
    out.layers->motion = motion_vectors(motion_scene(in, camera), background, diffuse ? &*diffuse : nullptr);
    r.layers_seconds = t0.seconds();
  }
  out.image = to_srgb8(colour);
  if (report) *report = r;
  return out;
}

}  // namespace spume
