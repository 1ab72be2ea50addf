#pragma once
// The GL headers, included one way everywhere, and the GL and OSMesa entry points spume calls. OSMesa
// (with the LLVM behind llvmpipe: about 45 MiB of pages touched when it loads) is opened when the first
// context is made (gl_library.cpp), not when spume starts, so a command that draws no surface never
// loads it. Each name below stands for the pointer read from libOSMesa then. Private to render/gl/.
#define GL_GLEXT_PROTOTYPES 1  // the prototypes give each pointer its type; nothing links to them
// clang-format off: glext.h needs the types from gl.h, which osmesa.h includes.
#include <GL/osmesa.h>
#include <GL/glext.h>
// clang-format on

// Every entry point spume calls; a new call needs its name here (the link fails without it).
#define SPUME_GL_FUNCTIONS(X) X(glActiveTexture) X(glAttachShader) X(glBindBuffer) X(glBindBufferBase) \
  X(glBindFramebuffer) X(glBindTexture) X(glBindVertexArray) X(glBufferData) X(glCheckFramebufferStatus) \
  X(glClearBufferfi) X(glClearBufferfv) X(glCompileShader) X(glCopyImageSubData) X(glCreateProgram) \
  X(glCreateShader) X(glCullFace) X(glDeleteBuffers) X(glDeleteFramebuffers) X(glDeleteProgram) \
  X(glDeleteShader) X(glDeleteTextures) X(glDeleteVertexArrays) X(glDepthFunc) X(glDepthMask) X(glDisable) \
  X(glDrawArrays) X(glDrawBuffers) X(glDrawElements) X(glEnable) X(glEnableVertexAttribArray) X(glFinish) \
  X(glFramebufferTexture2D) X(glFrontFace) X(glGenBuffers) X(glGenFramebuffers) X(glGenTextures) \
  X(glGenVertexArrays) X(glGetError) X(glGetIntegerv) X(glGetProgramInfoLog) X(glGetProgramiv) \
  X(glGetShaderInfoLog) X(glGetShaderiv) X(glGetString) X(glGetUniformLocation) X(glLinkProgram) \
  X(glPixelStorei) X(glPolygonOffset) X(glProgramUniform3f) X(glReadBuffer) X(glReadPixels) \
  X(glShaderSource) X(glStencilFunc) X(glStencilMask) X(glStencilOp) X(glTexParameteri) X(glTexStorage2D) \
  X(glUniform1f) X(glUniform1i) X(glUniform3f) X(glUniformMatrix4fv) X(glUseProgram) \
  X(glVertexAttribPointer) X(glViewport) X(OSMesaCreateContextAttribs) X(OSMesaDestroyContext) \
  X(OSMesaGetCurrentContext) X(OSMesaMakeCurrent)

#include <span>

namespace spume::gl {

struct Functions {
#define SPUME_GL_POINTER(name) decltype(&::name) p_##name = nullptr;
  SPUME_GL_FUNCTIONS(SPUME_GL_POINTER)
#undef SPUME_GL_POINTER
};

// libOSMesa's entry points, the library opened on the first call (thread-safe). Throws Error naming
// the library and what is missing when it cannot be opened or lacks an entry point.
const Functions& functions();
// The entry points from the first of `libraries` that opens (what functions() does with
// libOSMesa's names); throws as functions() does.
Functions load_functions(std::span<const char* const> libraries);

}  // namespace spume::gl

#define glActiveTexture (spume::gl::functions().p_glActiveTexture)
#define glAttachShader (spume::gl::functions().p_glAttachShader)
#define glBindBuffer (spume::gl::functions().p_glBindBuffer)
#define glBindBufferBase (spume::gl::functions().p_glBindBufferBase)
#define glBindFramebuffer (spume::gl::functions().p_glBindFramebuffer)
#define glBindTexture (spume::gl::functions().p_glBindTexture)
#define glBindVertexArray (spume::gl::functions().p_glBindVertexArray)
#define glBufferData (spume::gl::functions().p_glBufferData)
#define glCheckFramebufferStatus (spume::gl::functions().p_glCheckFramebufferStatus)
#define glClearBufferfi (spume::gl::functions().p_glClearBufferfi)
#define glClearBufferfv (spume::gl::functions().p_glClearBufferfv)
#define glCompileShader (spume::gl::functions().p_glCompileShader)
#define glCopyImageSubData (spume::gl::functions().p_glCopyImageSubData)
#define glCreateProgram (spume::gl::functions().p_glCreateProgram)
#define glCreateShader (spume::gl::functions().p_glCreateShader)
#define glCullFace (spume::gl::functions().p_glCullFace)
#define glDeleteBuffers (spume::gl::functions().p_glDeleteBuffers)
#define glDeleteFramebuffers (spume::gl::functions().p_glDeleteFramebuffers)
#define glDeleteProgram (spume::gl::functions().p_glDeleteProgram)
#define glDeleteShader (spume::gl::functions().p_glDeleteShader)
#define glDeleteTextures (spume::gl::functions().p_glDeleteTextures)
#define glDeleteVertexArrays (spume::gl::functions().p_glDeleteVertexArrays)
#define glDepthFunc (spume::gl::functions().p_glDepthFunc)
#define glDepthMask (spume::gl::functions().p_glDepthMask)
#define glDisable (spume::gl::functions().p_glDisable)
#define glDrawArrays (spume::gl::functions().p_glDrawArrays)
#define glDrawBuffers (spume::gl::functions().p_glDrawBuffers)
#define glDrawElements (spume::gl::functions().p_glDrawElements)
#define glEnable (spume::gl::functions().p_glEnable)
#define glEnableVertexAttribArray (spume::gl::functions().p_glEnableVertexAttribArray)
#define glFinish (spume::gl::functions().p_glFinish)
#define glFramebufferTexture2D (spume::gl::functions().p_glFramebufferTexture2D)
#define glFrontFace (spume::gl::functions().p_glFrontFace)
#define glGenBuffers (spume::gl::functions().p_glGenBuffers)
#define glGenFramebuffers (spume::gl::functions().p_glGenFramebuffers)
#define glGenTextures (spume::gl::functions().p_glGenTextures)
#define glGenVertexArrays (spume::gl::functions().p_glGenVertexArrays)
#define glGetError (spume::gl::functions().p_glGetError)
#define glGetIntegerv (spume::gl::functions().p_glGetIntegerv)
#define glGetProgramInfoLog (spume::gl::functions().p_glGetProgramInfoLog)
#define glGetProgramiv (spume::gl::functions().p_glGetProgramiv)
#define glGetShaderInfoLog (spume::gl::functions().p_glGetShaderInfoLog)
#define glGetShaderiv (spume::gl::functions().p_glGetShaderiv)
#define glGetString (spume::gl::functions().p_glGetString)
#define glGetUniformLocation (spume::gl::functions().p_glGetUniformLocation)
#define glLinkProgram (spume::gl::functions().p_glLinkProgram)
#define glPixelStorei (spume::gl::functions().p_glPixelStorei)
#define glPolygonOffset (spume::gl::functions().p_glPolygonOffset)
#define glProgramUniform3f (spume::gl::functions().p_glProgramUniform3f)
#define glReadBuffer (spume::gl::functions().p_glReadBuffer)
#define glReadPixels (spume::gl::functions().p_glReadPixels)
#define glShaderSource (spume::gl::functions().p_glShaderSource)
#define glStencilFunc (spume::gl::functions().p_glStencilFunc)
#define glStencilMask (spume::gl::functions().p_glStencilMask)
#define glStencilOp (spume::gl::functions().p_glStencilOp)
#define glTexParameteri (spume::gl::functions().p_glTexParameteri)
#define glTexStorage2D (spume::gl::functions().p_glTexStorage2D)
#define glUniform1f (spume::gl::functions().p_glUniform1f)
#define glUniform1i (spume::gl::functions().p_glUniform1i)
#define glUniform3f (spume::gl::functions().p_glUniform3f)
#define glUniformMatrix4fv (spume::gl::functions().p_glUniformMatrix4fv)
#define glUseProgram (spume::gl::functions().p_glUseProgram)
#define glVertexAttribPointer (spume::gl::functions().p_glVertexAttribPointer)
#define glViewport (spume::gl::functions().p_glViewport)
#define OSMesaCreateContextAttribs (spume::gl::functions().p_OSMesaCreateContextAttribs)
#define OSMesaDestroyContext (spume::gl::functions().p_OSMesaDestroyContext)
#define OSMesaGetCurrentContext (spume::gl::functions().p_OSMesaGetCurrentContext)
#define OSMesaMakeCurrent (spume::gl::functions().p_OSMesaMakeCurrent)
