// Writes out/tests/volume_preview.png: spray above, foam on and bubbles under a water plane, a
// solid post in front, composited over a sky/water gradient. For looking at, not a golden image.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "render/image/png_io.h"
#include "render/surface/triangle_mesh.h"
#include "render/volume/composite.h"
#include "render/volume/volume_pass.h"

namespace spume {
namespace {

TEST(VolumePreview, WritesAPicture) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  DiffuseFrame f;
  for (int i = 0; i < 60000; ++i) {
    const float x = u(rng), z = u(rng);
    const float crest = std::exp(-8.0f * (x - 0.2f * z) * (x - 0.2f * z));  // a band of spray and foam
    if (std::abs(u(rng)) > crest) continue;
    const float k = std::abs(u(rng));
    DiffuseType t = k < 0.3f ? DiffuseType::Spray : k < 0.75f ? DiffuseType::Foam : DiffuseType::Bubble;
    const float y = t == DiffuseType::Spray ? 0.02f + 0.5f * crest * std::abs(u(rng)) : t == DiffuseType::Foam ? 0.01f * u(rng) : -0.3f * std::abs(u(rng));
    f.positions.push_back(Vec3f(x, y, z));
    f.types.push_back(t);
  }
  Camera cam;
  cam.position = Vec3f(0.0f, 0.9f, 2.6f), cam.target = Vec3f(0.0f, -0.05f, 0.0f);
  cam.width = 320, cam.height = 180;
  TriangleMesh water, post;
  water.vertices = {{-9, 0, -9}, {-9, 0, 9}, {9, 0, 9}, {9, 0, -9}};
  water.indices = {0, 1, 2, 0, 2, 3};
  post.vertices = {{0.55f, -1, 0.9f}, {0.7f, -1, 0.9f}, {0.7f, 0.8f, 0.9f}, {0.55f, 0.8f, 0.9f}};
  post.indices = {0, 1, 2, 0, 2, 3};
  VolumeSettings s;
  s.look[size_t(DiffuseType::Spray)] = {0.004f, Vec3f(1.0f, 1.0f, 1.0f)};
  s.look[size_t(DiffuseType::Foam)] = {0.008f, Vec3f(0.92f, 0.95f, 1.0f)};
  s.look[size_t(DiffuseType::Bubble)] = {0.006f, Vec3f(0.85f, 0.95f, 1.0f)};
  s.alpha = 60.0f;
  s.samples_per_pixel = 4;
  VolumeStats st;
  const VolumeImage vol = render_volume(f, cam, s, {&water, &post}, &st);
  ImageRGBf back(cam.width, cam.height);
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const Ray r = cam.ray(x + 0.5f, y + 0.5f);
      // Stand-in for the OSMesa pass: water below the horizon, sky above, the post in brown.
      back.at(x, y) = r.direction.y() < 0.0f ? Vec3f(0.02f, 0.12f, 0.18f) : Vec3f(0.35f, 0.55f, 0.85f);
      const float t = (0.9f - r.origin.z()) / r.direction.z();
      const Vec3f p = r.origin + t * r.direction;
      if (t > 0.0f && p.x() > 0.55f && p.x() < 0.7f && p.y() < 0.8f) back.at(x, y) = Vec3f(0.3f, 0.2f, 0.12f);
    }
  const std::filesystem::path out = std::filesystem::path(SPUME_OUT_DIR) / "tests" / "volume_preview.png";
  write_png(out, to_srgb8(composite(vol, back)));
  EXPECT_FALSE(st.skipped);
  EXPECT_GT(st.intervals, 1000u);
  EXPECT_TRUE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace spume
