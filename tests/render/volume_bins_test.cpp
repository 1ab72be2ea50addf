// The screen-bin candidate search's pieces that the fast paths rewrote: the batched sphere
// projection against the scalar one and against brute-force ray/sphere tests, and the tile rays'
// hoisted camera against Camera::ray.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "sim/core/rng.h"
#include "render/volume/ray_sphere.h"
#include "render/volume/screen_bins.h"
#include "render/volume/tile_rays.h"

namespace spume {
namespace {

std::vector<Camera> cameras() {
  std::vector<Camera> out;
  Camera c;
  c.position = Vec3f(0.3f, 0.4f, 3.0f), c.target = Vec3f(0.0f, 0.0f, 0.0f), c.fov_y_degrees = 30.0f;
  c.width = 70, c.height = 45;
  out.push_back(c);
  c.position = Vec3f(-2.0f, 1.5f, 0.5f), c.target = Vec3f(0.2f, 0.1f, -0.3f), c.fov_y_degrees = 70.0f;
  c.width = 33, c.height = 64;
  out.push_back(c);
  c.position = Vec3f(0.0f, 4.0f, 0.0f), c.target = Vec3f(0.0f, 0.0f, 0.0f), c.fov_y_degrees = 45.0f;  // straight down
  c.width = 48, c.height = 40;
  out.push_back(c);
  return out;
}

// Spheres all around the camera: behind it, through its plane, off the image and in view; radii
// from tiny to large, some zero (not drawn).
void random_spheres(const Camera& cam, uint64_t seed, size_t n, std::vector<Vec3f>& centre, std::vector<float>& radius) {
  centre.resize(n), radius.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const auto u = random_uniform4({seed, RandomPurpose::Test, 0, i, 0});
    centre[i] = cam.target + 4.0f * Vec3f(u[0] - 0.5f, u[1] - 0.5f, u[2] - 0.5f) * (i % 7 == 0 ? 3.0f : 1.0f);
    radius[i] = i % 11 == 0 ? 0.0f : 0.002f + 0.3f * u[3] * u[3];
  }
}

TEST(VolumeBins, BatchedProjectionEqualsPixelRect) {
  for (const Camera& cam : cameras())
    for (auto [lo, hi] : {std::pair{0.5, 0.5}, std::pair{0.0, 1.0}}) {
      const SphereProjector proj(cam, lo, hi);
      std::vector<Vec3f> c;
      std::vector<float> r;
      random_spheres(cam, 7, 1000, c, r);
      size_t seen = 0;
      for (size_t b = 0; b < c.size(); b += SphereProjector::kBatch) {
        const size_t m = std::min(SphereProjector::kBatch, c.size() - b);
        SphereProjector::Rects q;
        proj.pixel_rects(c.data() + b, r.data() + b, m, q);
        for (size_t j = 0; j < m; ++j) {
          int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
          const bool hit = r[b + j] > 0.0f && proj.pixel_rect(c[b + j], r[b + j], x0, y0, x1, y1);
          ASSERT_EQ(hit, q.x0[j] <= q.x1[j]) << "sphere " << b + j;
          if (!hit) continue;
          ++seen;
          EXPECT_EQ(x0, q.x0[j]) << "sphere " << b + j;
          EXPECT_EQ(x1, q.x1[j]) << "sphere " << b + j;
          EXPECT_EQ(y0, q.y0[j]) << "sphere " << b + j;
          EXPECT_EQ(y1, q.y1[j]) << "sphere " << b + j;
        }
      }
      EXPECT_GT(seen, 100u);  // the case mix covers visible spheres too
    }
}

// Every pixel whose centre ray crosses a sphere (chord by ray_sphere_chord, in double) lies in
// the sphere's batched rectangle.
TEST(VolumeBins, BatchedRectanglesHoldEveryHitPixel) {
  for (const Camera& cam : cameras()) {
    const SphereProjector proj(cam, 0.5, 0.5);
    std::vector<Vec3f> c;
    std::vector<float> r;
    random_spheres(cam, 11, 256, c, r);
    const Vec3d o = cam.position.cast<double>();
    size_t hits = 0;
    for (size_t b = 0; b < c.size(); b += SphereProjector::kBatch) {
      const size_t m = std::min(SphereProjector::kBatch, c.size() - b);
      SphereProjector::Rects q;
      proj.pixel_rects(c.data() + b, r.data() + b, m, q);
      for (size_t j = 0; j < m; ++j) {
        const Vec3d oc = c[b + j].cast<double>() - o;
        const double r2 = double(r[b + j]) * double(r[b + j]);
        for (int y = 0; y < cam.height; ++y)
          for (int x = 0; x < cam.width; ++x) {
            double t0, t1;
            const Vec3d d = unit_double(cam.ray(float(x) + 0.5f, float(y) + 0.5f).direction);
            if (!(r2 > 0.0) || !ray_sphere_chord(oc, oc.squaredNorm(), d, r2, t0, t1) || t1 <= 0.0) continue;
            ++hits;
            EXPECT_TRUE(x >= q.x0[j] && x <= q.x1[j] && y >= q.y0[j] && y <= q.y1[j])
                << "sphere " << b + j << " hit at pixel " << x << "," << y << " outside [" << q.x0[j] << ".." << q.x1[j] << "] x ["
                << q.y0[j] << ".." << q.y1[j] << "]";
          }
      }
    }
    EXPECT_GT(hits, 1000u);
  }
}

TEST(VolumeBins, EyeRayDirectionsAreCameraRayBitForBit) {
  for (const Camera& cam : cameras()) {
    const EyeRayDirections eye(cam);
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x)
        for (float j : {0.5f, 0.0f, 0.999f, 0.3141f}) {
          const Vec3f a = eye(float(x) + j, float(y) + 1.0f - j), b = cam.ray(float(x) + j, float(y) + 1.0f - j).direction;
          ASSERT_EQ(0, std::memcmp(a.data(), b.data(), sizeof(float) * 3)) << "pixel " << x << "," << y << " jitter " << j;
        }
  }
}

}  // namespace
}  // namespace spume
