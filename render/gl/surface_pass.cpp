#include "render/gl/surface_pass.h"

#include <chrono>
#include <cmath>

#include "sim/core/error.h"
#include "render/gl/gl_objects.h"
#include "render/gl/sun_shadow.h"
#include "render/gl/surface_shaders.h"
#include "render/gl/surface_targets.h"
#include "render/gl/surface_view.h"
#include "render/surface/mesh_primitives.h"

namespace spume {
namespace {

constexpr float kInf = INFINITY;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Times the stages: GL queues its work, so each lap first waits for it (glFinish); otherwise a stage's
// cost would be counted in whichever later stage happens to wait.
class StageClock {
 public:
  double lap() {
    glFinish();
    const Clock::time_point now = Clock::now();
    const double dt = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return dt;
  }

 private:
  Clock::time_point last_ = Clock::now();
};

bool shows_water(const SurfaceScene& scene) { return scene.fluid && !scene.fluid->empty(); }

// Where the read-back finds the three outputs: a framebuffer and colour attachment each (the colour
// is attachment 0).
struct Outputs {
  GLuint colour_fb, depth_fb, opaque_fb;
  GLenum depth_attachment, opaque_attachment;
};

static_assert(sizeof(Vec3f) == 3 * sizeof(float), "colour rows are read as packed RGB floats");

}  // namespace

bool SurfaceScene::shows_geometry() const {
  if (fluid && !fluid->empty()) return true;
  for (const SceneSolid& s : solids)
    if (s.mesh && !s.mesh->empty()) return true;
  return false;
}

float ground_extent(const Environment& env) { return 4.0f * env.haze_distance; }

// The GL state kept between frames (context, programs, meshes, shadow map, targets) and the pass's
// steps, each leaving the state the next one expects.
struct SurfacePass::Gpu {
  OsmesaContext context;
  GlProgram sky, solid, ground, back, water_normal, water;
  std::unique_ptr<GlProgram> downsample;  // compiled on the first supersampled frame
  GLuint empty_vao = 0, env_ubo = 0, frame_ubo = 0;
  GpuMesh fluid, ground_quad;
  SunShadow shadow;
  std::vector<std::unique_ptr<GpuMesh>> solids, slabs;  // slabs: the walls' shadow casters
  SurfaceTargets targets;

  explicit Gpu(const OsmesaOptions& options)
      : context(1, 1, options),  // a 1x1 drawable: every pass renders into framebuffer objects
        sky(shaders::sky_vertex(), shaders::sky_fragment(), "sky"),
        solid(shaders::mesh_vertex(), shaders::solid_fragment(), "solids"),
        ground(shaders::mesh_vertex(), shaders::ground_fragment(), "ground"),
        back(shaders::mesh_vertex(), shaders::depth_only_fragment(), "water back faces"),
        water_normal(shaders::mesh_vertex(), shaders::water_normal_fragment(), "water normals"),
        water(shaders::sky_vertex(), shaders::water_fragment(), "water") {
    glGenVertexArrays(1, &empty_vao);
    glGenBuffers(1, &env_ubo);
    glGenBuffers(1, &frame_ubo);
    check_gl("creating the surface pass");
  }
  ~Gpu() {
    context.ensure_current();  // the members' GL objects are deleted after this body, in this context
    glDeleteBuffers(1, &frame_ubo);
    glDeleteBuffers(1, &env_ubo);
    glDeleteVertexArrays(1, &empty_vao);
  }

  // The solids (and the slabs that cast the shadows of walls) to the GPU, into buffers kept per solid
  // from frame to frame; adds their triangles and returns what casts the sun's shadow.
  std::vector<SunShadow::Caster> upload_solids(const std::vector<SceneSolid>& scene_solids, size_t& triangles) {
    while (solids.size() < scene_solids.size()) solids.push_back(std::make_unique<GpuMesh>());
    if (slabs.size() < scene_solids.size()) slabs.resize(scene_solids.size());  // made when needed
    std::vector<SunShadow::Caster> casters;
    for (size_t i = 0; i < scene_solids.size(); ++i) {
      const SceneSolid& s = scene_solids[i];
      if (!s.mesh || s.mesh->empty()) continue;
      solids[i]->upload(*s.mesh);
      triangles += s.mesh->triangle_count();
      const bool has_slabs = s.shadow_caster && !s.shadow_caster->empty();
      if (has_slabs) {
        if (!slabs[i]) slabs[i] = std::make_unique<GpuMesh>();
        slabs[i]->upload(*s.shadow_caster);
      }
      SunShadow::Caster c{has_slabs ? slabs[i].get() : solids[i].get(), s.offset, {}, has_slabs};
      for (const Vec3f& v : (has_slabs ? s.shadow_caster : s.mesh)->vertices) c.bounds.extend(v + s.offset);
      casters.push_back(c);
    }
    return casters;
  }

  void upload_fluid(const SurfaceScene& scene, size_t& triangles) {
    if (!shows_water(scene)) return;
    fluid.upload(*scene.fluid);
    triangles += scene.fluid->triangle_count();
  }

  // What every later pass reads: the Env and Frame blocks, the shadow map at unit 3; and the state the
  // shadow map changed, the viewport, back to the frame's. The projection is upside down, which turns
  // the front faces clockwise.
  void set_frame_inputs(const SurfaceScene& scene, const SurfaceView& view, bool shadows) {
    const EnvBlock env = env_block(scene.environment, scene.water);
    const shaders::FrameBlock frame = frame_block(view, shadow, shadows);
    glBindBuffer(GL_UNIFORM_BUFFER, env_ubo);
    glBufferData(GL_UNIFORM_BUFFER, sizeof env, &env, GL_STREAM_DRAW);
    glBindBuffer(GL_UNIFORM_BUFFER, frame_ubo);
    glBufferData(GL_UNIFORM_BUFFER, sizeof frame, &frame, GL_STREAM_DRAW);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, env_ubo);
    glBindBufferBase(GL_UNIFORM_BUFFER, 1, frame_ubo);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, shadow.texture());
    glActiveTexture(GL_TEXTURE0);
    glViewport(0, 0, view.camera.width, view.camera.height);
    glFrontFace(GL_CW);
  }

  // Pass 1: solids, then the ground, then the sky where nothing was drawn (on the far plane): front to
  // back, so the depth test rejects hidden fragments before they are shaded.
  void draw_opaque(const SurfaceScene& scene, const Vec3f& eye) {
    targets.bind_and_clear_opaque();
    glDisable(GL_CULL_FACE);  // solids are two-sided (a tank is seen from inside)
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    draw_solids(scene.solids);
    draw_ground(scene.environment, eye);
    draw_sky();
    check_gl("drawing the opaque scene");
  }

  void draw_solids(const std::vector<SceneSolid>& scene_solids) {
    solid.use();
    const GLint offset_loc = glGetUniformLocation(solid.id(), "u_offset");
    const GLint albedo_loc = glGetUniformLocation(solid.id(), "u_albedo");
    for (size_t i = 0; i < scene_solids.size(); ++i) {
      const SceneSolid& s = scene_solids[i];
      if (!s.mesh || s.mesh->empty()) continue;
      glUniform3f(offset_loc, s.offset.x(), s.offset.y(), s.offset.z());
      glUniform3f(albedo_loc, s.albedo.x(), s.albedo.y(), s.albedo.z());
      solids[i]->draw();
    }
  }

  // A quad centred under the eye, large enough that the haze hides its edge; none from below.
  void draw_ground(const Environment& e, const Vec3f& eye) {
    if (!(e.ground && eye.y() > e.ground_height)) return;
    const float ext = ground_extent(e);
    ground_quad.upload(make_quad_mesh(Vec3f(eye.x() - ext, e.ground_height, eye.z() - ext), Vec3f(0, 0, 2 * ext),
                                      Vec3f(2 * ext, 0, 0)));
    ground.use();
    glUniform3f(glGetUniformLocation(ground.id(), "u_offset"), 0, 0, 0);
    ground_quad.draw();
  }

  // A full-screen triangle on the far plane: passes the depth test (LEQUAL) only where nothing was
  // drawn, and leaves the depth buffer as it is.
  void draw_sky() {
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    sky.use();
    draw_full_screen();
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
  }

  void draw_full_screen() const {
    glBindVertexArray(empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

  // Pass 2: the nearest back faces: where view rays leave the water (the path they travel through it).
  void draw_water_back_faces() {
    targets.bind_and_clear_back_faces();
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    back.use();
    glProgramUniform3f(back.id(), glGetUniformLocation(back.id(), "u_offset"), 0, 0, 0);
    fluid.draw();
  }

  // Pass 3: the front faces' normals and depths over copies of the opaque image and depths (the
  // solids in front still hide the water); the stencil marks the pixels they cover.
  void draw_water_front_faces() {
    targets.copy_opaque_to_final();
    targets.front_faces.bind();
    glCullFace(GL_BACK);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xFF);
    glStencilFunc(GL_ALWAYS, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    water_normal.use();
    glProgramUniform3f(water_normal.id(), glGetUniformLocation(water_normal.id(), "u_offset"), 0, 0, 0);
    fluid.draw();
  }

  // Pass 4: shades each pixel the stencil marks, once (the stencil test runs before the shader, so a
  // full-screen triangle costs only the water's pixels), into the copy of the opaque image.
  void shade_water() {
    targets.final_image.bind();
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glStencilFunc(GL_EQUAL, 1, 0xFF);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    water.use();
    // The units of surface_shaders.h's water shader; unit 3 keeps the sun's shadow map.
    const GLuint inputs[6] = {targets.opaque_colour.id(), targets.opaque_depth.id(), targets.back_z.id(), 0,
                              targets.front_normal.id(), targets.final_depth.id()};
    for (GLuint unit = 0; unit < 6; ++unit) {
      if (unit == 3) continue;
      glActiveTexture(GL_TEXTURE0 + unit);
      glBindTexture(GL_TEXTURE_2D, inputs[unit]);
    }
    glActiveTexture(GL_TEXTURE0);
    draw_full_screen();
    glDisable(GL_STENCIL_TEST);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    check_gl("drawing the water");
  }

  // Without supersampling the outputs are read from the targets as drawn: the image with the water
  // when there is water, else the opaque one.
  Outputs full_size_outputs(bool with_water) const {
    return {with_water ? targets.final_image.id() : targets.opaque.id(),
            with_water ? targets.front_faces.id() : targets.opaque.id(), targets.opaque.id(), GL_COLOR_ATTACHMENT1,
            GL_COLOR_ATTACHMENT1};
  }

  // Pass 5, supersampling only: box-filters colour and takes the nearest depths into the resolved
  // targets of the output size (out_w x out_h), so that only the output's pixels are read back.
  Outputs downsample_outputs(bool with_water, int supersample, int out_w, int out_h) {
    targets.resolved.bind();
    glViewport(0, 0, out_w, out_h);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    if (!downsample)
      downsample = std::make_unique<GlProgram>(shaders::sky_vertex(), shaders::downsample_fragment(), "down-sampling");
    downsample->use();
    const GLuint inputs[3] = {with_water ? targets.final_colour.id() : targets.opaque_colour.id(),
                              with_water ? targets.final_depth.id() : targets.opaque_depth.id(),
                              targets.opaque_depth.id()};
    for (GLuint unit = 0; unit < 3; ++unit) {
      glActiveTexture(GL_TEXTURE0 + unit);
      glBindTexture(GL_TEXTURE_2D, inputs[unit]);
    }
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(glGetUniformLocation(downsample->id(), "u_ss"), supersample);
    draw_full_screen();
    const GLuint r = targets.resolved.id();
    return {r, r, r, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  }

  // Reads the float targets back as they are, straight into the image's arrays (llvmpipe copies them;
  // about 5 ms at 1920x1080).
  static SurfaceImage read_back(const Outputs& from, int w, int h) {
    SurfaceImage out;
    out.colour = ImageRGBf(w, h);
    out.depth.resize(size_t(w) * h);
    out.opaque_depth.resize(size_t(w) * h);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    auto read = [&](GLuint fb, GLenum attachment, GLenum format, float* dst) {
      glBindFramebuffer(GL_READ_FRAMEBUFFER, fb);
      glReadBuffer(attachment);
      glReadPixels(0, 0, w, h, format, GL_FLOAT, dst);
    };
    read(from.colour_fb, GL_COLOR_ATTACHMENT0, GL_RGB, out.colour.rgb.front().data());
    read(from.depth_fb, from.depth_attachment, GL_RED, out.depth.data());
    read(from.opaque_fb, from.opaque_attachment, GL_RED, out.opaque_depth.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    check_gl("reading the surface pass back");
    return out;
  }
};

SurfacePass::SurfacePass(const SurfacePassOptions& options) : options_(options) {
  if (options_.supersample < 1 || options_.supersample > 4)
    fail("surface pass: supersample must be 1..4, got ", options_.supersample);
}

SurfacePass::~SurfacePass() = default;

SurfaceImage SurfacePass::render(const SurfaceScene& scene, const Camera& camera, SurfacePassStats* stats) {
  const Clock::time_point start = Clock::now();
  SurfacePassStats st;
  SurfaceImage out =
      scene.shows_geometry() ? render_gl(scene, camera, st) : render_background(scene.environment, camera);
  st.seconds = seconds_since(start);
  if (stats) *stats = st;
  return out;
}

SurfaceImage SurfacePass::render_gl(const SurfaceScene& scene, const Camera& camera, SurfacePassStats& st) {
  StageClock clock;
  if (!gpu_) {
    gpu_ = std::make_unique<Gpu>(options_.gl);
    st.seconds_context = clock.lap();
  }
  Gpu& g = *gpu_;
  g.context.ensure_current();
  st.used_gl = true;
  const int ss = options_.supersample;
  const SurfaceView view = surface_view(scene, camera, ss);
  g.targets.resize(view.camera.width, view.camera.height, camera.width, camera.height);

  const std::vector<SunShadow::Caster> casters = g.upload_solids(scene.solids, st.triangles);
  g.upload_fluid(scene, st.triangles);
  st.seconds_upload = clock.lap();
  const bool shadows = g.shadow.render(casters, scene.environment.sun_direction);
  st.seconds_shadow = clock.lap();

  g.set_frame_inputs(scene, view, shadows);
  g.draw_opaque(scene, view.camera.position);
  st.seconds_opaque = clock.lap();
  const bool water = shows_water(scene);
  if (water) {
    g.draw_water_back_faces();
    st.seconds_water_back = clock.lap();
    g.draw_water_front_faces();
    g.shade_water();
    st.seconds_water_front = clock.lap();
  }

  const Outputs outputs =
      ss > 1 ? g.downsample_outputs(water, ss, camera.width, camera.height) : g.full_size_outputs(water);
  st.seconds_resolve = clock.lap();
  SurfaceImage out = Gpu::read_back(outputs, camera.width, camera.height);
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
