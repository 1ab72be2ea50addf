// Screen-space motion vectors (frame/motion_vectors.h) against the pinhole projection worked out by
// hand: a camera moving past a wall, water rising, a box sliding, a particle crossing the sky.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/frame/motion_vectors.h"

namespace spume {
namespace {

constexpr int kW = 64, kH = 48;
constexpr double kDt = 0.04;  // s, 25 fps

Camera camera_at_x(float x) {
  Camera c;
  c.position = Vec3f(x, 0.0f, 5.0f);
  c.target = Vec3f(x, 0.0f, 0.0f);
  c.fov_y_degrees = 40.0f;
  c.width = kW, c.height = kH;
  return c;
}

// Pixels per metre across the view at planar depth d.
double px_per_m(double d) { return 0.5 * kH / (d * std::tan(20.0 * std::numbers::pi / 180.0)); }

// Everything at planar depth `depth`; water in front of the ground where `water`.
SurfaceImage flat(float depth, bool water) {
  SurfaceImage s;
  s.colour = ImageRGBf(kW, kH), s.opaque_colour = ImageRGBf(kW, kH);
  s.depth.assign(size_t(kW) * kH, depth);
  s.opaque_depth.assign(size_t(kW) * kH, water ? depth + 1.0f : depth);
  return s;
}

MotionScene still_scene() {
  MotionScene m;
  m.previous = m.now = m.next = camera_at_x(0.0f);
  m.frame_seconds = kDt;
  return m;
}

const Rgba& at(const std::vector<Rgba>& mv, int x, int y) { return mv[size_t(y) * kW + size_t(x)]; }

// The camera moves 0.1 m to the right per frame past a still wall 5 m away: the wall moves left by
// 0.1 m at 5 m, forward and back alike.
TEST(MotionVectors, AStillWallMovesAgainstACameraTrackingPastIt) {
  MotionScene m = still_scene();
  m.previous = camera_at_x(-0.1f), m.next = camera_at_x(0.1f);
  const std::vector<Rgba> mv = motion_vectors(m, flat(5.0f, false), nullptr);
  const double expected = 0.1 * px_per_m(5.0);
  for (auto [x, y] : {std::pair{32, 24}, {3, 7}, {60, 40}}) {
    EXPECT_NEAR(at(mv, x, y)[0], -expected, 2e-3 * expected) << x << "," << y;
    EXPECT_NEAR(at(mv, x, y)[1], 0.0f, 1e-3f);
    EXPECT_NEAR(at(mv, x, y)[2], expected, 2e-3 * expected);
  }
}

// Water rising at 2 m/s, from a lattice of fluid particles all moving so: forward v (up) is
// 2 * 0.04 m at 5 m.
TEST(MotionVectors, WaterMovesWithTheFluidNearItsSurface) {
  MotionScene m = still_scene();
  std::vector<Vec3f> x, v;
  for (int i = -30; i <= 30; ++i)
    for (int j = -30; j <= 30; ++j)
      for (int k = -2; k <= 2; ++k) x.push_back(Vec3f(0.05f * i, 0.05f * j, 0.05f * k)), v.push_back(Vec3f(0, 2, 0));
  m.fluid_positions = x, m.fluid_velocities = v, m.fluid_support = 0.1f;
  const std::vector<Rgba> mv = motion_vectors(m, flat(5.0f, true), nullptr);
  const double expected = 2.0 * kDt * px_per_m(5.0);
  EXPECT_NEAR(at(mv, 32, 24)[1], expected, 0.01 * expected);
  EXPECT_NEAR(at(mv, 32, 24)[0], 0.0f, 1e-3f);
  EXPECT_NEAR(at(mv, 32, 24)[3], -expected, 0.01 * expected);
  m.fluid_velocities = {};  // a cache without velocities: the water stands still
  EXPECT_EQ(at(motion_vectors(m, flat(5.0f, true), nullptr), 32, 24)[1], 0.0f);
}

// A box whose front face is the surface 5 m away, sliding left at 1.5 m/s; the ground beside it is still.
TEST(MotionVectors, ASolidMovesWithItsRigidMotion) {
  MotionScene m = still_scene();
  Solid box;
  box.kind = Solid::Kind::Box;
  box.min = Vec3f(-1, -1, -1), box.max = Vec3f(1, 1, 0);  // its face z = 0 is 5 m from the camera
  box.velocity = Vec3f(-1.5f, 0, 0);
  const SolidSet solids({box});
  m.solids = &solids;
  const std::vector<Rgba> mv = motion_vectors(m, flat(5.0f, false), nullptr);
  const double expected = 1.5 * kDt * px_per_m(5.0);
  EXPECT_NEAR(at(mv, 32, 24)[0], -expected, 0.01 * expected) << "on the box's face";
  EXPECT_EQ(at(mv, 1, 1)[0], 0.0f) << "beyond the box (|x| > 1 m at 5 m is outside it)";
}

// A foam particle crossing the sky at 3 m/s, 3 m from the camera: where it is fully opaque the pixel
// takes its motion; where it is half transparent, half of it (the sky stands still).
TEST(MotionVectors, DiffuseMaterialMixesItsMotionByItsOpacity) {
  MotionScene m = still_scene();
  DiffusePoints d;
  d.positions = {Vec3f(0, 0, 2)}, d.types = {DiffuseType::Foam};
  const std::vector<Vec3f> v = {Vec3f(3, 0, 0)};
  m.diffuse = &d, m.diffuse_velocities = v, m.radius = {0.1f, 0.1f, 0.1f};
  VolumeImage volume;
  volume.width = kW, volume.height = kH;
  volume.transmittance.assign(size_t(kW) * kH, 1.0f);
  volume.transmittance[size_t(24) * kW + 32] = 0.0f;
  volume.transmittance[size_t(24) * kW + 31] = 0.5f;
  SurfaceImage sky = flat(0.0f, false);
  std::fill(sky.depth.begin(), sky.depth.end(), INFINITY), std::fill(sky.opaque_depth.begin(), sky.opaque_depth.end(), INFINITY);
  const std::vector<Rgba> mv = motion_vectors(m, sky, &volume);
  // Projection of x = 3 * 0.04 at planar depth 3 (the particle's centre; the camera is at z = 5).
  const double expected = 3.0 * kDt * px_per_m(3.0);
  EXPECT_NEAR(at(mv, 32, 24)[0], expected, 0.01 * expected);
  EXPECT_NEAR(at(mv, 32, 24)[2], -expected, 0.01 * expected);
  EXPECT_NEAR(at(mv, 31, 24)[0], 0.5 * expected, 0.01 * expected);
  EXPECT_EQ(at(mv, 10, 10)[0], 0.0f) << "the sky far from the particle";
}

}  // namespace
}  // namespace spume
