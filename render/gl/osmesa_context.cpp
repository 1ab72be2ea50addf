#include "render/gl/osmesa_context.h"

#include <cstdlib>
#include <string>

#include "sim/core/error.h"
#include "render/gl/gl_api.h"

namespace spume {

OsmesaContext::OsmesaContext(int width, int height, const OsmesaOptions& options) {
  if (options.llvmpipe_threads >= 0) setenv("LP_NUM_THREADS", std::to_string(options.llvmpipe_threads).c_str(), 1);
  // Asking for 3.3 core gives Mesa's highest core version (4.5 on llvmpipe).
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         24,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_ACCUM_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         3,
                         0};
  context_ = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!context_) fail("OSMesa: could not create a core-profile OpenGL context (is libosmesa6 llvmpipe installed?)");
  make_current(width, height);
  auto text = [](GLenum name) {
    const auto* s = reinterpret_cast<const char*>(glGetString(name));
    return std::string(s ? s : "?");
  };
  renderer_ = text(GL_RENDERER), version_ = text(GL_VERSION);
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45) {
    OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
    fail("OSMesa: need OpenGL 4.5 core, got ", version_, " (", renderer_, ")");
  }
}

OsmesaContext::~OsmesaContext() {
  if (context_) OSMesaDestroyContext(static_cast<OSMesaContext>(context_));
}

void OsmesaContext::make_current(int width, int height) {
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    fail("OSMesa: buffer size ", width, "x", height, " is outside 1..16384");
  if (width != width_ || height != height_) buffer_.assign(size_t(width) * size_t(height) * 4, 0);
  width_ = width, height_ = height;
  if (!OSMesaMakeCurrent(static_cast<OSMesaContext>(context_), buffer_.data(), GL_UNSIGNED_BYTE, width, height))
    fail("OSMesa: could not make the context current on a ", width, "x", height, " buffer");
}

void OsmesaContext::ensure_current() {
  if (OSMesaGetCurrentContext() != static_cast<OSMesaContext>(context_)) make_current(width_, height_);
}

void check_gl(const char* where) {
  GLenum first = glGetError();
  if (first == GL_NO_ERROR) return;
  while (glGetError() != GL_NO_ERROR) {
  }
  fail("OpenGL error 0x", std::hex, first, " in ", where);
}

}  // namespace spume
