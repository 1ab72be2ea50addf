#include "render/gl/surface_pass.h"

#include <cmath>

#include "sim/core/error.h"
#include "sim/core/stopwatch.h"
#include "render/gl/surface_gpu.h"

namespace spume {
namespace {

constexpr float kInf = INFINITY;

// Times the stages: GL queues its work, so each lap first waits for it (glFinish); otherwise a stage's
// cost would be counted in whichever later stage happens to wait.
class StageClock {
 public:
  double lap() {
    glFinish();
    const double dt = since_last_.seconds();
    since_last_.restart();
    return dt;
  }

 private:
  Stopwatch since_last_;
};

}  // namespace

bool SurfaceScene::shows_water() const { return fluid && !fluid->empty(); }

bool SurfaceScene::shows_geometry() const {
  if (shows_water()) return true;
  for (const SceneSolid& s : solids)
    if (s.mesh && !s.mesh->empty()) return true;
  return false;
}

float ground_extent(const Environment& env) { return 4.0f * env.haze_distance; }

SurfacePass::SurfacePass(const SurfacePassOptions& options) : options_(options) {
  if (options_.supersample < 1 || options_.supersample > 4)
    fail("surface pass: supersample must be 1..4, got ", options_.supersample);
}

SurfacePass::~SurfacePass() = default;

SurfaceImage SurfacePass::render(const SurfaceScene& scene, const Camera& camera, SurfacePassStats* stats) {
  const Stopwatch stopwatch;
  SurfacePassStats st;
  SurfaceImage out =
      scene.shows_geometry() ? render_gl(scene, camera, st) : render_background(scene.environment, camera);
  if (options_.opaque_colour && out.opaque_colour.pixel_count() == 0) out.opaque_colour = out.colour;
  st.seconds = stopwatch.seconds();
  if (stats) *stats = st;
  return out;
}

SurfaceImage SurfacePass::render_gl(const SurfaceScene& scene, const Camera& camera, SurfacePassStats& st) {
  StageClock clock;
  if (!gpu_) {  // the first frame with geometry; the context and programs serve every later frame
    gpu_ = std::make_unique<Gpu>(options_.gl);
    st.seconds_context = clock.lap();
  }
  Gpu& g = *gpu_;
  g.context.ensure_current();
  st.used_gl = true;
  const int ss = options_.supersample;
  const SurfaceView view = surface_view(scene, camera, ss);  // drawn at ss x the output size per axis
  g.targets.resize(view.camera.width, view.camera.height, camera.width, camera.height);

  const std::vector<SunShadow::Caster> casters = g.upload_solids(scene.solids, st.triangles);
  g.upload_fluid(scene, st.triangles);
  st.seconds_upload = clock.lap();
  const bool shadows = g.shadow.render(casters, scene.environment.sun_direction);
  st.seconds_shadow = clock.lap();

  g.set_frame_inputs(scene, view, shadows);
  g.draw_opaque(scene, view.camera.position);
  st.seconds_opaque = clock.lap();
  const bool water = scene.shows_water();
  if (water) {
    g.draw_water_back_faces();
    st.seconds_water_back = clock.lap();
    g.draw_water_front_faces();
    g.shade_water();
    st.seconds_water_front = clock.lap();
  }

  const SurfaceOutputs outputs =
      ss > 1 ? g.downsample_outputs(water, ss, camera.width, camera.height) : g.full_size_outputs(water);
  st.seconds_resolve = clock.lap();
  SurfaceImage out = Gpu::read_back(outputs, camera.width, camera.height, options_.opaque_colour);
  st.seconds_readback = clock.lap();
  return out;
}

SurfaceImage render_background(const Environment& env, const Camera& camera) {
  SurfaceImage out;
  out.colour = ImageRGBf(camera.width, camera.height);
  out.depth.assign(out.colour.pixel_count(), kInf);
  Vec3f right, up, back;
  camera.basis(right, up, back);
  const float ext = ground_extent(env);
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const Ray r = camera.ray(float(x) + 0.5f, float(y) + 0.5f);
      Vec3f c = env.sky(r.direction, true);
      float depth = kInf;
      if (env.ground && r.direction.y() < 0.0f && r.origin.y() > env.ground_height) {
        const Vec3f p = r.origin + r.direction * ((env.ground_height - r.origin.y()) / r.direction.y());
        if (std::abs(p.x() - r.origin.x()) < ext && std::abs(p.z() - r.origin.z()) < ext) {
          c = env.ground_radiance(p, r.origin);
          depth = (r.origin - p).dot(back);
        }
      }
      out.colour.at(x, y) = c;
      out.depth[size_t(y) * camera.width + x] = depth;
    }
  out.opaque_depth = out.depth;
  return out;
}

}  // namespace spume
