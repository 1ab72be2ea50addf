// The camera basis, including the views that used to be degenerate (looking along the up vector).
#include <gtest/gtest.h>

#include "render/camera/camera.h"

namespace spume {
namespace {

Camera looking(const Vec3f& position, const Vec3f& target) {
  Camera c;
  c.position = position, c.target = target, c.up = Vec3f::UnitY();
  c.width = 64, c.height = 36, c.fov_y_degrees = 40.0f;
  return c;
}

void expect_orthonormal(const Camera& c) {
  Vec3f right, up, back;
  c.basis(right, up, back);
  ASSERT_TRUE(finite(right) && finite(up) && finite(back));
  EXPECT_NEAR(right.norm(), 1.0f, 1e-5f);
  EXPECT_NEAR(up.norm(), 1.0f, 1e-5f);
  EXPECT_NEAR(right.dot(up), 0.0f, 1e-5f);
  EXPECT_NEAR(right.dot(back), 0.0f, 1e-5f);
  EXPECT_NEAR(up.dot(back), 0.0f, 1e-5f);
}

TEST(Camera, ALevelViewKeepsYUp) {
  const Camera c = looking({0, 1, 5}, {0, 1, 0});
  expect_orthonormal(c);
  Vec3f right, up, back;
  c.basis(right, up, back);
  EXPECT_NEAR((right - Vec3f::UnitX()).norm(), 0.0f, 1e-6f);
  EXPECT_NEAR((up - Vec3f::UnitY()).norm(), 0.0f, 1e-6f);
}

TEST(Camera, StraightDownShowsXToTheRightAndMinusZUp) {
  const Camera c = looking({0.5f, 3, 0.5f}, {0.5f, 0, 0.5f});
  expect_orthonormal(c);
  Vec3f right, up, back;
  c.basis(right, up, back);
  EXPECT_NEAR((right - Vec3f::UnitX()).norm(), 0.0f, 1e-6f);
  EXPECT_NEAR((up + Vec3f::UnitZ()).norm(), 0.0f, 1e-6f);
  // The centre ray points straight down; a ray to the right of centre leans to +x.
  const Ray centre = c.ray(32, 18), right_ray = c.ray(60, 18);
  EXPECT_NEAR((centre.direction + Vec3f::UnitY()).norm(), 0.0f, 1e-5f);
  EXPECT_GT(right_ray.direction.x(), 0.1f);
  const Eigen::Matrix4f view = c.view_matrix();
  EXPECT_TRUE(view.allFinite());
}

TEST(Camera, StraightUpIsFiniteToo) {
  expect_orthonormal(looking({0, -3, 0}, {0, 0, 0}));
  expect_orthonormal(looking({0, 0, 0}, {0, 1e-3f, 0}));
}

}  // namespace
}  // namespace spume
