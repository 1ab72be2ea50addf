#pragma once
// Pinhole camera. Pixel (x, y) has x to the right and y DOWN from the top-left corner, its centre at
// (x + 0.5, y + 0.5); images are stored top row first. The OSMesa pass uses view_matrix() and
// projection_matrix() and the Embree pass uses ray(), so both see the same picture.
#include <vector>

#include <Eigen/Core>

#include "render/keys/render_keys.h"
#include "sim/core/vec.h"

namespace spume {

struct Ray {
  Vec3f origin;
  Vec3f direction;  // unit
};

struct Camera {
  Vec3f position = Vec3f(0, 1, 3);   // m
  Vec3f target = Vec3f::Zero();      // m, looked at
  Vec3f up = Vec3f::UnitY();
  float fov_y_degrees = declared_float(keys::render::camera_fov);  // vertical field of view
  int width = int(keys::render::resolution.value[0]);   // pixels, by default render.resolution's
  int height = int(keys::render::resolution.value[1]);

  // Orthonormal basis: right, true up, backward (camera looks along -back).
  void basis(Vec3f& right, Vec3f& true_up, Vec3f& back) const;
  // Ray through image point (px, py) in pixels (e.g. x + 0.5 for a pixel centre).
  Ray ray(float px, float py) const;
  Eigen::Matrix4f view_matrix() const;
  // OpenGL clip-space projection; depth maps [near, far] to [-1, 1].
  Eigen::Matrix4f projection_matrix(float near_plane, float far_plane) const;
};

// A camera keyframe; cameras between keys are interpolated linearly (position, target, fov).
struct CameraKey {
  double time = 0.0;  // s
  Vec3f position = Vec3f(0, 1, 3), target = Vec3f::Zero();
  float fov_y_degrees = declared_float(keys::render::key_fov);
};

// The camera at time t: clamped to the first/last key outside their range. Keys sorted by time.
Camera camera_at(const std::vector<CameraKey>& keys, double t, int width, int height);

}  // namespace spume
