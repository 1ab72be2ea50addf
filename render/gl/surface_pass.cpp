#include "render/gl/surface_pass.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "render/gl/gl_objects.h"
#include "render/gl/sun_shadow.h"
#include "render/surface/mesh_primitives.h"
#include "render/gl/surface_shaders.h"

namespace spume {
namespace {

constexpr float kInf = INFINITY;

// Eigen stores column-major, as GLSL expects.
void put_matrix(float* dst, const Eigen::Matrix4f& m) { std::memcpy(dst, m.data(), 16 * sizeof(float)); }

// Near and far planes around everything drawn: tight planes keep the depth buffer precise.
std::pair<float, float> clip_planes(const SurfaceScene& scene, const Camera& camera) {
  Vec3f right, up, back;
  camera.basis(right, up, back);
  float near_d = kInf, far_d = 0.0f;
  auto add = [&](const Vec3f& p) {
    const float z = (camera.position - p).dot(back);  // distance along the view axis
    near_d = std::min(near_d, z), far_d = std::max(far_d, z);
  };
  auto add_mesh = [&](const TriangleMesh* m, const Vec3f& offset) {
    if (!m) return;
    Aabb box;
    for (const Vec3f& v : m->vertices) box.extend(v + offset);
    if (box.empty()) return;
    for (int c = 0; c < 8; ++c)
      add(Vec3f(c & 1 ? box.max.x() : box.min.x(), c & 2 ? box.max.y() : box.min.y(),
                c & 4 ? box.max.z() : box.min.z()));
  };
  add_mesh(scene.fluid, Vec3f::Zero());
  for (const SceneSolid& s : scene.solids) add_mesh(s.mesh, s.offset);
  const Environment& env = scene.environment;
  if (env.ground) {
    const float g = ground_extent(env);
    for (int c = 0; c < 4; ++c)
      add(Vec3f(camera.position.x() + (c & 1 ? g : -g), env.ground_height, camera.position.z() + (c & 2 ? g : -g)));
    near_d = std::min(near_d, camera.position.y() - env.ground_height);
  }
  far_d = std::max(far_d * 1.01f, 1e-2f);
  near_d = std::clamp(0.5f * near_d, std::max(1e-3f, far_d * 1e-5f), 0.5f * far_d);
  return {near_d, far_d};
}

static_assert(sizeof(Vec3f) == 3 * sizeof(float), "colour rows are read as packed RGB floats");

}  // namespace

bool SurfaceScene::shows_geometry() const {
  if (fluid && !fluid->empty()) return true;
  for (const SceneSolid& s : solids)
    if (s.mesh && !s.mesh->empty()) return true;
  return false;
}

float ground_extent(const Environment& env) { return 4.0f * env.haze_distance; }

struct SurfacePass::Gpu {
  OsmesaContext context;
  GlProgram sky, solid, ground, back, water_normal, water;
  std::unique_ptr<GlProgram> downsample;  // compiled on the first supersampled frame
  GLuint empty_vao = 0, env_ubo = 0, frame_ubo = 0;
  GpuMesh fluid, ground_quad;
  SunShadow shadow;
  std::vector<std::unique_ptr<GpuMesh>> solids, slabs;  // slabs: the walls' shadow casters
  int width = 0, height = 0;
  // Targets: opaque (A), water back faces (B), water front faces' normals (G) and the final image (C),
  // G and C sharing a depth-stencil buffer whose stencil marks the water's pixels.
  GlTexture a_colour, a_depth, a_z, b_z, g_normal, c_colour, c_depth, c_z;
  GlFramebuffer a, b, g, c;
  int out_width = 0, out_height = 0;
  // Supersampling only: the down-sampled colour, depth and opaque depth.
  GlTexture r_colour, r_depth, r_opaque;
  GlFramebuffer r;

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

  // Targets of w x h (supersampled) and, when that differs, the down-sampled out_w x out_h.
  void resize(int w, int h, int out_w, int out_h) {
    if ((out_w != out_width || out_h != out_height) && (out_w != w || out_h != h)) {
      out_width = out_w, out_height = out_h;
      r_colour = GlTexture(GL_RGBA32F, out_w, out_h);
      r_depth = GlTexture(GL_R32F, out_w, out_h), r_opaque = GlTexture(GL_R32F, out_w, out_h);
      const GLuint ids[3] = {r_colour.id(), r_depth.id(), r_opaque.id()};
      r = GlFramebuffer(ids, 0, "down-sampled output");
    }
    if (w == width && h == height) return;
    width = w, height = h;
    a_colour = GlTexture(GL_RGBA16F, w, h);
    a_depth = GlTexture(GL_R32F, w, h);
    // Every byte of the targets is allocated and cleared on the first frame (about 4 ms per 8 MB at
    // 1920x1080): 4-byte depth-stencil (24-bit depth is as fine as a 32-bit float's over the [0.5, 1)
    // of window depth where the scenes lie) and 10-bit normals.
    a_z = GlTexture(GL_DEPTH24_STENCIL8, w, h);  // the format of c_z, so it copies
    b_z = GlTexture(GL_DEPTH_COMPONENT32F, w, h);
    g_normal = GlTexture(GL_RGB10_A2, w, h);
    c_colour = GlTexture(GL_RGBA16F, w, h);
    c_depth = GlTexture(GL_R32F, w, h);
    c_z = GlTexture(GL_DEPTH24_STENCIL8, w, h);
    const GLuint ac[] = {a_colour.id(), a_depth.id()}, gc[] = {g_normal.id(), c_depth.id()}, cc[] = {c_colour.id()};
    a = GlFramebuffer(ac, a_z.id(), "opaque", GL_DEPTH_STENCIL_ATTACHMENT);
    b = GlFramebuffer({}, b_z.id(), "water back faces");
    g = GlFramebuffer(gc, c_z.id(), "water normals", GL_DEPTH_STENCIL_ATTACHMENT);
    c = GlFramebuffer(cc, c_z.id(), "final", GL_DEPTH_STENCIL_ATTACHMENT);
  }

  // Binds f and clears it: colour to black, linear depth to +inf, depth buffer to the far plane
  // and the stencil to 0 (the opaque target), or only the depth buffer (the back faces' target).
  static void bind_and_clear(const GlFramebuffer& f, bool opaque) {
    const float black[4] = {0, 0, 0, 1}, inf[4] = {kInf, kInf, kInf, kInf}, one = 1.0f;
    f.bind();
    glDepthMask(GL_TRUE);
    if (opaque) {
      glClearBufferfv(GL_COLOR, 0, black);
      glClearBufferfv(GL_COLOR, 1, inf);
      glStencilMask(0xFF);
      glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
    } else {
      glClearBufferfv(GL_DEPTH, 0, &one);
    }
  }

  void copy(const GlTexture& from, const GlTexture& to) const {
    glCopyImageSubData(from.id(), GL_TEXTURE_2D, 0, 0, 0, 0, to.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
  }
};

SurfacePass::SurfacePass(const SurfacePassOptions& options) : options_(options) {
  if (options_.supersample < 1 || options_.supersample > 4)
    fail("surface pass: supersample must be 1..4, got ", options_.supersample);
}

SurfacePass::~SurfacePass() = default;

SurfaceImage SurfacePass::render(const SurfaceScene& scene, const Camera& camera, SurfacePassStats* stats) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto lap = [t = start]() mutable {
    glFinish();
    const auto now = clock::now();
    const double dt = std::chrono::duration<double>(now - t).count();
    t = now;
    return dt;
  };
  SurfacePassStats st;
  SurfaceImage out;
  if (!scene.shows_geometry()) {
    out = render_background(scene.environment, camera);
  } else {
    if (!gpu_) {
      gpu_ = std::make_unique<Gpu>(options_.gl);
      st.seconds_context = lap();
    }
    Gpu& g = *gpu_;
    g.context.ensure_current();
    st.used_gl = true;
    const int ss = options_.supersample, W = camera.width * ss, H = camera.height * ss;
    g.resize(W, H, camera.width, camera.height);
    Camera cam = camera;
    cam.width = W, cam.height = H;
    const auto [near_d, far_d] = clip_planes(scene, camera);
    // Drawn upside down (y negated in clip space, so the winding flips too): GL's bottom-up rows then
    // read back in the image's top-first order.
    Eigen::Matrix4f proj = cam.projection_matrix(near_d, far_d);
    proj.row(1) *= -1.0f;
    const Eigen::Matrix4f view = cam.view_matrix(), vp = proj * view;

    // Solids (and the slabs that cast the shadows of walls) to the GPU, then their shadow map.
    while (g.solids.size() < scene.solids.size()) g.solids.push_back(std::make_unique<GpuMesh>());
    if (g.slabs.size() < scene.solids.size()) g.slabs.resize(scene.solids.size());  // made when needed
    std::vector<SunShadow::Caster> casters;
    for (size_t i = 0; i < scene.solids.size(); ++i) {
      const SceneSolid& s = scene.solids[i];
      if (!s.mesh || s.mesh->empty()) continue;
      g.solids[i]->upload(*s.mesh);
      st.triangles += s.mesh->triangle_count();
      const bool slabs = s.shadow_caster && !s.shadow_caster->empty();
      if (slabs) {
        if (!g.slabs[i]) g.slabs[i] = std::make_unique<GpuMesh>();
        g.slabs[i]->upload(*s.shadow_caster);
      }
      SunShadow::Caster c{slabs ? g.slabs[i].get() : g.solids[i].get(), s.offset, {}, slabs};
      for (const Vec3f& v : (slabs ? s.shadow_caster : s.mesh)->vertices) c.bounds.extend(v + s.offset);
      casters.push_back(c);
    }
    if (scene.fluid && !scene.fluid->empty()) {
      g.fluid.upload(*scene.fluid);
      st.triangles += scene.fluid->triangle_count();
    }
    st.seconds_upload = lap();
    const bool shadows = g.shadow.render(casters, scene.environment.sun_direction);
    st.seconds_shadow = lap();

    const EnvBlock env = env_block(scene.environment, scene.water);
    shaders::FrameBlock frame{};
    put_matrix(frame.view_proj, vp);
    put_matrix(frame.inv_view, view.inverse());
    put_matrix(frame.inv_view_proj, vp.inverse());
    for (int i = 0; i < 3; ++i) frame.eye[i] = cam.position[i];
    frame.proj[0] = proj(0, 0), frame.proj[1] = proj(1, 1), frame.proj[2] = near_d, frame.proj[3] = far_d;
    frame.viewport[0] = float(W), frame.viewport[1] = float(H);
    frame.viewport[2] = 1.0f / float(W), frame.viewport[3] = 1.0f / float(H);
    put_matrix(frame.sun_view_proj, g.shadow.view_proj());
    frame.shadow[0] = shadows ? 1.0f : 0.0f;
    frame.shadow[1] = 1.0f / SunShadow::kSize;
    frame.shadow[3] = g.shadow.texel_size();
    glBindBuffer(GL_UNIFORM_BUFFER, g.env_ubo);
    glBufferData(GL_UNIFORM_BUFFER, sizeof env, &env, GL_STREAM_DRAW);
    glBindBuffer(GL_UNIFORM_BUFFER, g.frame_ubo);
    glBufferData(GL_UNIFORM_BUFFER, sizeof frame, &frame, GL_STREAM_DRAW);
    glBindBufferBase(GL_UNIFORM_BUFFER, 0, g.env_ubo);
    glBindBufferBase(GL_UNIFORM_BUFFER, 1, g.frame_ubo);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, g.shadow.texture());
    glActiveTexture(GL_TEXTURE0);
    glViewport(0, 0, W, H);
    glFrontFace(GL_CW);

    // Pass 1: solids, then the ground, then the sky where nothing was drawn (on the far plane):
    // front to back, so the depth test rejects hidden fragments before they are shaded.
    Gpu::bind_and_clear(g.a, true);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    g.solid.use();
    const GLint offset_loc = glGetUniformLocation(g.solid.id(), "u_offset");
    const GLint albedo_loc = glGetUniformLocation(g.solid.id(), "u_albedo");
    for (size_t i = 0; i < scene.solids.size(); ++i) {
      const SceneSolid& s = scene.solids[i];
      if (!s.mesh || s.mesh->empty()) continue;
      glUniform3f(offset_loc, s.offset.x(), s.offset.y(), s.offset.z());
      glUniform3f(albedo_loc, s.albedo.x(), s.albedo.y(), s.albedo.z());
      g.solids[i]->draw();
    }
    const Environment& e = scene.environment;
    if (e.ground && cam.position.y() > e.ground_height) {
      const float ext = ground_extent(e);
      g.ground_quad.upload(make_quad_mesh(Vec3f(cam.position.x() - ext, e.ground_height, cam.position.z() - ext),
                                          Vec3f(0, 0, 2 * ext), Vec3f(2 * ext, 0, 0)));
      g.ground.use();
      glUniform3f(glGetUniformLocation(g.ground.id(), "u_offset"), 0, 0, 0);
      g.ground_quad.draw();
    }
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    g.sky.use();
    glBindVertexArray(g.empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    check_gl("drawing the opaque scene");
    st.seconds_opaque = lap();

    const bool water = scene.fluid && !scene.fluid->empty();
    if (water) {
      // Pass 2: the nearest back faces: where view rays leave the water.
      Gpu::bind_and_clear(g.b, false);
      glEnable(GL_CULL_FACE);
      glCullFace(GL_FRONT);
      g.back.use();
      glProgramUniform3f(g.back.id(), glGetUniformLocation(g.back.id(), "u_offset"), 0, 0, 0);
      g.fluid.draw();
      st.seconds_water_back = lap();
      // Pass 3: the front faces' normals and depths over copies of the opaque image and depths; the
      // stencil marks the pixels they cover.
      g.copy(g.a_colour, g.c_colour), g.copy(g.a_depth, g.c_depth), g.copy(g.a_z, g.c_z);
      g.g.bind();
      glCullFace(GL_BACK);
      glEnable(GL_STENCIL_TEST);
      glStencilMask(0xFF);
      glStencilFunc(GL_ALWAYS, 1, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      g.water_normal.use();
      glProgramUniform3f(g.water_normal.id(), glGetUniformLocation(g.water_normal.id(), "u_offset"), 0, 0, 0);
      g.fluid.draw();
      // Pass 4: shade each marked pixel once (the stencil test runs before the shader).
      g.c.bind();
      glDisable(GL_DEPTH_TEST);
      glDisable(GL_CULL_FACE);
      glStencilFunc(GL_EQUAL, 1, 0xFF);
      glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
      g.water.use();
      const GLuint inputs[6] = {g.a_colour.id(), g.a_depth.id(), g.b_z.id(), 0, g.g_normal.id(), g.c_depth.id()};
      for (GLuint unit = 0; unit < 6; ++unit) {
        if (unit == 3) continue;  // the sun's shadow map
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, inputs[unit]);
      }
      glActiveTexture(GL_TEXTURE0);
      glBindVertexArray(g.empty_vao);
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glDisable(GL_STENCIL_TEST);
      glEnable(GL_DEPTH_TEST);
      glDisable(GL_CULL_FACE);
      check_gl("drawing the water");
      st.seconds_water_front = lap();
    }
    // Read the float targets back as they are (llvmpipe copies them; about 5 ms at 1920x1080). With
    // supersampling, first box-filter them into targets of the output size.
    GLuint colour_fb = water ? g.c.id() : g.a.id(), depth_fb = water ? g.g.id() : g.a.id(), opaque_fb = g.a.id();
    GLenum depth_att = GL_COLOR_ATTACHMENT1, opaque_att = GL_COLOR_ATTACHMENT1;
    if (ss > 1) {
      g.r.bind();
      glViewport(0, 0, camera.width, camera.height);
      glDisable(GL_DEPTH_TEST);
      glDisable(GL_CULL_FACE);
      if (!g.downsample)
        g.downsample = std::make_unique<GlProgram>(shaders::sky_vertex(), shaders::downsample_fragment(), "down-sampling");
      g.downsample->use();
      const GLuint inputs[3] = {water ? g.c_colour.id() : g.a_colour.id(), water ? g.c_depth.id() : g.a_depth.id(),
                                g.a_depth.id()};
      for (GLuint unit = 0; unit < 3; ++unit) {
        glActiveTexture(GL_TEXTURE0 + unit);
        glBindTexture(GL_TEXTURE_2D, inputs[unit]);
      }
      glActiveTexture(GL_TEXTURE0);
      glUniform1i(glGetUniformLocation(g.downsample->id(), "u_ss"), ss);
      glBindVertexArray(g.empty_vao);
      glDrawArrays(GL_TRIANGLES, 0, 3);
      colour_fb = depth_fb = opaque_fb = g.r.id();
      depth_att = GL_COLOR_ATTACHMENT1, opaque_att = GL_COLOR_ATTACHMENT2;
    }
    st.seconds_resolve = lap();
    // Straight into the output's arrays.
    const int w = camera.width, h = camera.height;
    out.colour = ImageRGBf(w, h);
    out.depth.resize(size_t(w) * h);
    out.opaque_depth.resize(size_t(w) * h);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    auto read = [&](GLuint fb, GLenum attachment, GLenum format, float* dst) {
      glBindFramebuffer(GL_READ_FRAMEBUFFER, fb);
      glReadBuffer(attachment);
      glReadPixels(0, 0, w, h, format, GL_FLOAT, dst);
    };
    read(colour_fb, GL_COLOR_ATTACHMENT0, GL_RGB, out.colour.rgb.front().data());
    read(depth_fb, depth_att, GL_RED, out.depth.data());
    read(opaque_fb, opaque_att, GL_RED, out.opaque_depth.data());
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    check_gl("reading the surface pass back");
    st.seconds_readback = lap();
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = st;
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
