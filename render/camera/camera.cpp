#include "render/camera/camera.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace spume {

void Camera::basis(Vec3f& right, Vec3f& true_up, Vec3f& back) const {
  back = (position - target).normalized();
  Vec3f side = up.cross(back);
  // Looking straight along the up vector (a top-down view) leaves no sideways direction: take the
  // world axis least aligned with the view instead (for a view straight down on +y up: -z is the
  // top of the picture), so the picture is never blank.
  if (side.norm() < 1e-4f * up.norm()) {
    int axis = 2;  // z first: a top-down view keeps x to the right
    for (int a : {0, 1})
      if (std::abs(back[a]) < std::abs(back[axis]) - 1e-4f) axis = a;
    Vec3f fallback = Vec3f::Zero();
    fallback[axis] = axis == 2 ? -1.0f : 1.0f;
    side = fallback.cross(back);
  }
  right = side.normalized();
  true_up = back.cross(right);
}

Ray Camera::ray(float px, float py) const {
  Vec3f right, true_up, back;
  basis(right, true_up, back);
  const float tan_half = std::tan(0.5f * fov_y_degrees * std::numbers::pi_v<float> / 180.0f);
  const float aspect = float(width) / float(height);
  const float sx = (2.0f * px / float(width) - 1.0f) * tan_half * aspect;
  const float sy = (1.0f - 2.0f * py / float(height)) * tan_half;
  return {position, (sx * right + sy * true_up - back).normalized()};
}

Eigen::Matrix4f Camera::view_matrix() const {
  Vec3f right, true_up, back;
  basis(right, true_up, back);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = right.transpose();
  m.block<1, 3>(1, 0) = true_up.transpose();
  m.block<1, 3>(2, 0) = back.transpose();
  m(0, 3) = -right.dot(position);
  m(1, 3) = -true_up.dot(position);
  m(2, 3) = -back.dot(position);
  return m;
}

Eigen::Matrix4f Camera::projection_matrix(float n, float f) const {
  const float t = 1.0f / std::tan(0.5f * fov_y_degrees * std::numbers::pi_v<float> / 180.0f);
  const float aspect = float(width) / float(height);
  Eigen::Matrix4f p = Eigen::Matrix4f::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = (f + n) / (n - f);
  p(2, 3) = 2.0f * f * n / (n - f);
  p(3, 2) = -1.0f;
  return p;
}

Camera camera_at(const std::vector<CameraKey>& keys, double t, int width, int height) {
  Camera c;
  c.width = width, c.height = height;
  if (keys.empty()) return c;
  auto apply = [&](const CameraKey& k) {
    c.position = k.position, c.target = k.target, c.fov_y_degrees = k.fov_y_degrees;
  };
  if (t <= keys.front().time) apply(keys.front());
  else if (t >= keys.back().time) apply(keys.back());
  else {
    const auto next = std::upper_bound(keys.begin(), keys.end(), t, [](double v, const CameraKey& k) { return v < k.time; });
    const CameraKey &b = *next, &a = *(next - 1);
    const float s = float((t - a.time) / (b.time - a.time));
    c.position = a.position + s * (b.position - a.position);
    c.target = a.target + s * (b.target - a.target);
    c.fov_y_degrees = a.fov_y_degrees + s * (b.fov_y_degrees - a.fov_y_degrees);
  }
  return c;
}

}  // namespace spume
