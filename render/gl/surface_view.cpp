#include "render/gl/surface_view.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>
#include <utility>

namespace spume {
namespace {

// Eigen stores column-major, as GLSL expects.
void put_matrix(float* dst, const Eigen::Matrix4f& m) { std::memcpy(dst, m.data(), 16 * sizeof(float)); }

// Near and far planes around everything drawn: tight planes keep the depth buffer precise.
std::pair<float, float> clip_planes(const SurfaceScene& scene, const Camera& camera) {
  Vec3f right, up, back;
  camera.basis(right, up, back);
  float near_d = INFINITY, far_d = 0.0f;
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

}  // namespace

SurfaceView surface_view(const SurfaceScene& scene, const Camera& camera, int supersample) {
  SurfaceView v;
  v.camera = camera;
  v.camera.width = camera.width * supersample, v.camera.height = camera.height * supersample;
  std::tie(v.near_d, v.far_d) = clip_planes(scene, camera);
  v.proj = v.camera.projection_matrix(v.near_d, v.far_d);
  v.proj.row(1) *= -1.0f;
  v.view = v.camera.view_matrix();
  v.view_proj = v.proj * v.view;
  return v;
}

shaders::FrameBlock frame_block(const SurfaceView& v, const SunShadow& shadow, bool shadows) {
  const float w = float(v.camera.width), h = float(v.camera.height);
  shaders::FrameBlock frame{};
  put_matrix(frame.view_proj, v.view_proj);
  put_matrix(frame.inv_view, v.view.inverse());
  put_matrix(frame.inv_view_proj, v.view_proj.inverse());
  for (int i = 0; i < 3; ++i) frame.eye[i] = v.camera.position[i];
  frame.proj[0] = v.proj(0, 0), frame.proj[1] = v.proj(1, 1), frame.proj[2] = v.near_d, frame.proj[3] = v.far_d;
  frame.viewport[0] = w, frame.viewport[1] = h;
  frame.viewport[2] = 1.0f / w, frame.viewport[3] = 1.0f / h;
  put_matrix(frame.sun_view_proj, shadow.view_proj());
  frame.shadow[0] = shadows ? 1.0f : 0.0f;
  frame.shadow[1] = 1.0f / SunShadow::kSize;
  frame.shadow[3] = shadow.texel_size();
  return frame;
}

}  // namespace spume
