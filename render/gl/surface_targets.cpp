#include "render/gl/surface_targets.h"

#include <cmath>

namespace spume {
namespace {

void copy_texture(const GlTexture& from, const GlTexture& to, int width, int height) {
  glCopyImageSubData(from.id(), GL_TEXTURE_2D, 0, 0, 0, 0, to.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
}

}  // namespace

void SurfaceTargets::resize(int w, int h, int out_w, int out_h) {
  if ((out_w != out_width || out_h != out_height) && (out_w != w || out_h != h)) {
    out_width = out_w, out_height = out_h;
    resolved_colour = GlTexture(GL_RGBA32F, out_w, out_h);
    resolved_depth = GlTexture(GL_R32F, out_w, out_h), resolved_opaque = GlTexture(GL_R32F, out_w, out_h);
    resolved_opaque_colour = GlTexture(GL_RGBA32F, out_w, out_h);
    const GLuint ids[4] = {resolved_colour.id(), resolved_depth.id(), resolved_opaque.id(), resolved_opaque_colour.id()};
    resolved = GlFramebuffer(ids, 0, "down-sampled output");
  }
  if (w == width && h == height) return;
  width = w, height = h;
  opaque_colour = GlTexture(GL_RGBA16F, w, h);
  opaque_depth = GlTexture(GL_R32F, w, h);
  // Every byte of the targets is allocated and cleared on the first frame (about 4 ms per 8 MB at
  // 1920x1080): 4-byte depth-stencil (24-bit depth is as fine as a 32-bit float's over the [0.5, 1)
  // of window depth where the scenes lie) and 10-bit normals.
  opaque_z = GlTexture(GL_DEPTH24_STENCIL8, w, h);  // the format of final_z, so it copies
  back_z = GlTexture(GL_DEPTH_COMPONENT32F, w, h);
  front_normal = GlTexture(GL_RGB10_A2, w, h);
  final_colour = GlTexture(GL_RGBA16F, w, h);
  final_depth = GlTexture(GL_R32F, w, h);
  final_z = GlTexture(GL_DEPTH24_STENCIL8, w, h);
  const GLuint oc[] = {opaque_colour.id(), opaque_depth.id()}, fc[] = {front_normal.id(), final_depth.id()},
               ic[] = {final_colour.id()};
  opaque = GlFramebuffer(oc, opaque_z.id(), "opaque", GL_DEPTH_STENCIL_ATTACHMENT);
  back_faces = GlFramebuffer({}, back_z.id(), "water back faces");
  front_faces = GlFramebuffer(fc, final_z.id(), "water normals", GL_DEPTH_STENCIL_ATTACHMENT);
  final_image = GlFramebuffer(ic, final_z.id(), "final", GL_DEPTH_STENCIL_ATTACHMENT);
}

void SurfaceTargets::bind_and_clear_opaque() const {
  const float black[4] = {0, 0, 0, 1}, inf[4] = {INFINITY, INFINITY, INFINITY, INFINITY};
  opaque.bind();
  glDepthMask(GL_TRUE);
  glClearBufferfv(GL_COLOR, 0, black);
  glClearBufferfv(GL_COLOR, 1, inf);
  glStencilMask(0xFF);
  glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
}

void SurfaceTargets::bind_and_clear_back_faces() const {
  const float one = 1.0f;
  back_faces.bind();
  glDepthMask(GL_TRUE);
  glClearBufferfv(GL_DEPTH, 0, &one);
}

void SurfaceTargets::copy_opaque_to_final() const {
  copy_texture(opaque_colour, final_colour, width, height);
  copy_texture(opaque_depth, final_depth, width, height);
  copy_texture(opaque_z, final_z, width, height);
}

}  // namespace spume
