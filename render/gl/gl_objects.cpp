#include "render/gl/gl_objects.h"

#include <utility>

#include "sim/core/error.h"
#include "render/gl/osmesa_context.h"

namespace spume {
namespace {

GLuint compile(GLenum stage, const std::string& source, const std::string& name) {
  const GLuint s = glCreateShader(stage);
  const char* text = source.c_str();
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    glDeleteShader(s);
    fail("GLSL ", stage == GL_VERTEX_SHADER ? "vertex" : "fragment", " shader of '", name, "' does not compile:\n",
         log);
  }
  return s;
}

}  // namespace

GlProgram::GlProgram(const std::string& vertex, const std::string& fragment, const std::string& name) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex, name), fs = compile(GL_FRAGMENT_SHADER, fragment, name);
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetProgramInfoLog(id_, sizeof log, nullptr, log);
    fail("GLSL program '", name, "' does not link:\n", log);
  }
}

GlProgram::~GlProgram() {
  if (id_) glDeleteProgram(id_);
}

GlProgram& GlProgram::operator=(GlProgram&& o) noexcept {
  std::swap(id_, o.id_);
  return *this;
}

GlTexture::GlTexture(GLenum internal_format, int width, int height) {
  // Bind-to-edit throughout: OSMesa does not export the 4.5 direct-state-access entry points.
  glGenTextures(1, &id_);
  glBindTexture(GL_TEXTURE_2D, id_);
  glTexStorage2D(GL_TEXTURE_2D, 1, internal_format, width, height);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glBindTexture(GL_TEXTURE_2D, 0);
  check_gl("creating a texture");
}

GlTexture::~GlTexture() {
  if (id_) glDeleteTextures(1, &id_);
}

GlTexture& GlTexture::operator=(GlTexture&& o) noexcept {
  std::swap(id_, o.id_);
  return *this;
}

GlFramebuffer::GlFramebuffer(std::span<const GLuint> colours, GLuint depth, const char* name, GLenum depth_attachment) {
  glGenFramebuffers(1, &id_);
  glBindFramebuffer(GL_FRAMEBUFFER, id_);
  std::vector<GLenum> draw;
  for (size_t i = 0; i < colours.size(); ++i) {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GLenum(GL_COLOR_ATTACHMENT0 + i), GL_TEXTURE_2D, colours[i], 0);
    draw.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
  }
  if (depth) glFramebufferTexture2D(GL_FRAMEBUFFER, depth_attachment, GL_TEXTURE_2D, depth, 0);
  glDrawBuffers(GLsizei(draw.size()), draw.data());
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    fail("OpenGL framebuffer '", name, "' is incomplete (status 0x", std::hex, status, ")");
}

GlFramebuffer::~GlFramebuffer() {
  if (id_) glDeleteFramebuffers(1, &id_);
}

GlFramebuffer& GlFramebuffer::operator=(GlFramebuffer&& o) noexcept {
  std::swap(id_, o.id_);
  return *this;
}

GpuMesh::GpuMesh() {
  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glGenBuffers(1, &ebo_);
  // Interleaved position (location 0) and normal (location 1), 6 floats a vertex.
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo_);  // recorded in the vertex array
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexAttribArray(a);
    glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<const void*>(size_t(a) * 3 * sizeof(float)));
  }
  glBindVertexArray(0);
}

GpuMesh::~GpuMesh() {
  glDeleteBuffers(1, &ebo_);
  glDeleteBuffers(1, &vbo_);
  glDeleteVertexArrays(1, &vao_);
}

void GpuMesh::upload(const TriangleMesh& mesh) {
  const std::vector<Vec3f> computed =
      mesh.normals.size() == mesh.vertices.size() ? std::vector<Vec3f>{} : face_weighted_normals(mesh);
  const std::vector<Vec3f>& normals = computed.empty() ? mesh.normals : computed;
  staging_.resize(mesh.vertices.size() * 6);
  for (size_t i = 0; i < mesh.vertices.size(); ++i)
    for (int a = 0; a < 3; ++a) staging_[6 * i + a] = mesh.vertices[i][a], staging_[6 * i + 3 + a] = normals[i][a];
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(staging_.size() * sizeof(float)), staging_.data(), GL_STREAM_DRAW);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(uint32_t)), mesh.indices.data(),
               GL_STREAM_DRAW);
  glBindVertexArray(0);
  count_ = GLsizei(mesh.indices.size());
  check_gl("uploading a mesh");
}

void GpuMesh::draw() const {
  if (count_ == 0) return;
  glBindVertexArray(vao_);
  glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
}

std::vector<Vec3f> face_weighted_normals(const TriangleMesh& mesh) {
  std::vector<Vec3f> n(mesh.vertices.size(), Vec3f::Zero());
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
    const Vec3f face =
        (mesh.vertices[b] - mesh.vertices[a]).cross(mesh.vertices[c] - mesh.vertices[a]);  // |face| = 2 area
    n[a] += face, n[b] += face, n[c] += face;
  }
  for (Vec3f& v : n) v = v.norm() > 0.0f ? Vec3f(v.normalized()) : Vec3f::UnitY();
  return n;
}

}  // namespace spume
