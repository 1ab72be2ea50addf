#pragma once
// Owning wrappers of the few GL objects the surface pass uses (programs, textures, framebuffers,
// meshes). Each deletes its object; none is copyable. Need a current context (OsmesaContext).
#include <span>
#include <string>
#include <vector>

#include "render/gl/gl_api.h"
#include "render/surface/triangle_mesh.h"

namespace spume {

class GlProgram {
 public:
  GlProgram() = default;
  // Compiles and links; throws Error with the driver's log, naming `name`.
  GlProgram(const std::string& vertex, const std::string& fragment, const std::string& name);
  ~GlProgram();
  GlProgram(GlProgram&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  GlProgram& operator=(GlProgram&& o) noexcept;
  GlProgram(const GlProgram&) = delete;
  void use() const { glUseProgram(id_); }
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

// A 2D texture of one format, nearest filtering, clamped: render targets and screen lookups.
class GlTexture {
 public:
  GlTexture() = default;
  GlTexture(GLenum internal_format, int width, int height);
  ~GlTexture();
  GlTexture(GlTexture&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  GlTexture& operator=(GlTexture&& o) noexcept;
  GlTexture(const GlTexture&) = delete;
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
};

// A framebuffer over textures: colour attachments 0..n-1 (all drawn) and an optional depth texture
// (a depth-stencil one with `depth_attachment` GL_DEPTH_STENCIL_ATTACHMENT).
class GlFramebuffer {
 public:
  GlFramebuffer() = default;
  GlFramebuffer(std::span<const GLuint> colours, GLuint depth, const char* name,
                GLenum depth_attachment = GL_DEPTH_ATTACHMENT);
  ~GlFramebuffer();
  GlFramebuffer(GlFramebuffer&& o) noexcept : id_(o.id_) { o.id_ = 0; }
  GlFramebuffer& operator=(GlFramebuffer&& o) noexcept;
  GlFramebuffer(const GlFramebuffer&) = delete;
  GLuint id() const { return id_; }
  void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, id_); }

 private:
  GLuint id_ = 0;
};

// A TriangleMesh in GPU buffers: position and normal per vertex (normals computed from the faces
// when the mesh has none), 32-bit indices.
class GpuMesh {
 public:
  GpuMesh();
  ~GpuMesh();
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
  void upload(const TriangleMesh& mesh);
  void draw() const;
  size_t triangles() const { return count_ / 3; }

 private:
  GLuint vao_ = 0, vbo_ = 0, ebo_ = 0;
  GLsizei count_ = 0;
  std::vector<float> staging_;
};

// Area-weighted vertex normals of a mesh that has none (unit; +y for unused vertices).
std::vector<Vec3f> face_weighted_normals(const TriangleMesh& mesh);

}  // namespace spume
