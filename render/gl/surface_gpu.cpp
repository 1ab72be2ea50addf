#include "render/gl/surface_gpu.h"

#include <cmath>

#include "sim/core/error.h"
#include "render/gl/surface_shaders.h"
#include "render/surface/mesh_primitives.h"

namespace spume {

static_assert(sizeof(Vec3f) == 3 * sizeof(float), "colour rows are read as packed RGB floats");

SurfacePass::Gpu::Gpu(const OsmesaOptions& options)
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

SurfacePass::Gpu::~Gpu() {
  context.ensure_current();  // the members' GL objects are deleted after this body, in this context
  glDeleteBuffers(1, &frame_ubo);
  glDeleteBuffers(1, &env_ubo);
  glDeleteVertexArrays(1, &empty_vao);
}

std::vector<SunShadow::Caster> SurfacePass::Gpu::upload_solids(const std::vector<SceneSolid>& scene_solids,
                                                               size_t& triangles) {
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

void SurfacePass::Gpu::upload_fluid(const SurfaceScene& scene, size_t& triangles) {
  if (!scene.shows_water()) return;
  fluid.upload(*scene.fluid);
  triangles += scene.fluid->triangle_count();
}

void SurfacePass::Gpu::set_frame_inputs(const SurfaceScene& scene, const SurfaceView& view, bool shadows) {
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

void SurfacePass::Gpu::draw_opaque(const SurfaceScene& scene, const Vec3f& eye) {
  targets.bind_and_clear_opaque();
  glDisable(GL_CULL_FACE);  // solids are two-sided (a tank is seen from inside)
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  draw_solids(scene.solids);
  draw_ground(scene.environment, eye);
  draw_sky();
  check_gl("drawing the opaque scene");
}

void SurfacePass::Gpu::draw_solids(const std::vector<SceneSolid>& scene_solids) {
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

void SurfacePass::Gpu::draw_ground(const Environment& e, const Vec3f& eye) {
  if (!(e.ground && eye.y() > e.ground_height)) return;
  const float ext = ground_extent(e);
  ground_quad.upload(make_quad_mesh(Vec3f(eye.x() - ext, e.ground_height, eye.z() - ext), Vec3f(0, 0, 2 * ext),
                                    Vec3f(2 * ext, 0, 0)));
  ground.use();
  glUniform3f(glGetUniformLocation(ground.id(), "u_offset"), 0, 0, 0);
  ground_quad.draw();
}

void SurfacePass::Gpu::draw_sky() {
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  sky.use();
  draw_full_screen();
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
}

void SurfacePass::Gpu::draw_full_screen() const {
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

void SurfacePass::Gpu::draw_water_back_faces() {
  targets.bind_and_clear_back_faces();
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);
  back.use();
  glProgramUniform3f(back.id(), glGetUniformLocation(back.id(), "u_offset"), 0, 0, 0);
  fluid.draw();
}

void SurfacePass::Gpu::draw_water_front_faces() {
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

void SurfacePass::Gpu::shade_water() {
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

SurfaceOutputs SurfacePass::Gpu::full_size_outputs(bool with_water) const {
  return {with_water ? targets.final_image.id() : targets.opaque.id(),
          with_water ? targets.front_faces.id() : targets.opaque.id(), targets.opaque.id(), targets.opaque.id(),
          GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT0};
}

SurfaceOutputs SurfacePass::Gpu::downsample_outputs(bool with_water, int supersample, int out_w, int out_h) {
  targets.resolved.bind();
  glViewport(0, 0, out_w, out_h);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  if (!downsample)
    downsample = std::make_unique<GlProgram>(shaders::sky_vertex(), shaders::downsample_fragment(), "down-sampling");
  downsample->use();
  const GLuint inputs[4] = {with_water ? targets.final_colour.id() : targets.opaque_colour.id(),
                            with_water ? targets.final_depth.id() : targets.opaque_depth.id(),
                            targets.opaque_depth.id(), targets.opaque_colour.id()};
  for (GLuint unit = 0; unit < 4; ++unit) {
    glActiveTexture(GL_TEXTURE0 + unit);
    glBindTexture(GL_TEXTURE_2D, inputs[unit]);
  }
  glActiveTexture(GL_TEXTURE0);
  glUniform1i(glGetUniformLocation(downsample->id(), "u_ss"), supersample);
  draw_full_screen();
  const GLuint r = targets.resolved.id();
  return {r, r, r, r, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3};
}

SurfaceImage SurfacePass::Gpu::read_back(const SurfaceOutputs& from, int w, int h, bool opaque_colour) {
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
  if (opaque_colour) {
    out.opaque_colour = ImageRGBf(w, h);
    read(from.opaque_colour_fb, from.opaque_colour_attachment, GL_RGB, out.opaque_colour.rgb.front().data());
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check_gl("reading the surface pass back");
  return out;
}

}  // namespace spume
