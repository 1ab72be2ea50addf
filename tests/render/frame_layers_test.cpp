// The EXR frames' layers (frame/frame_layers.h): each diffuse type's part of Eq. 9 worked out by hand,
// the parts summing to the whole, the layers rebuilding beauty, and Z as the distance along the ray.
#include <gtest/gtest.h>

#include <cmath>

#include "render/frame/frame_layers.h"
#include "render/volume/absorption.h"
#include "render/volume/composite.h"
#include "render/volume/volume_pass.h"

namespace spume {
namespace {

constexpr size_t kSpray = size_t(DiffuseType::Spray), kFoam = size_t(DiffuseType::Foam),
                 kBubble = size_t(DiffuseType::Bubble);

void expect_near3(const Vec3d& a, const Vec3d& b, double tol) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(a[c], b[c], tol) << "channel " << c;
}

// Spray over [0, 1] and foam over [0.5, 2] along one ray, alpha 1: the union is 2 long, the types'
// lengths 1 and 1.5, so spray owns 1/2.5 of the optical depth and foam 1.5/2.5.
TEST(AbsorptionSplit, OverlappingTypesShareTheOpacityByTheirOpticalDepth) {
  VolumeShading shading;
  shading.alpha = 1.0;
  shading.color[kSpray] = Vec3d(1, 0, 0), shading.color[kFoam] = Vec3d(0, 1, 0), shading.color[kBubble] = Vec3d(0, 0, 1);
  Interval iv[2] = {{0.0f, 1.0f, uint32_t(kSpray)}, {0.5f, 2.0f, uint32_t(kFoam)}};
  RayTypes t;
  const RaySample s = absorb_intervals(iv, 2, shading, {}, &t);
  EXPECT_NEAR(s.transmittance, std::exp(-2.0), 1e-12);
  EXPECT_NEAR(t.share[kSpray], 0.4, 1e-12);
  EXPECT_NEAR(t.share[kFoam], 0.6, 1e-12);
  EXPECT_EQ(t.share[kBubble], 0.0);
  expect_near3(t.type_color[kSpray], Vec3d(0.4, 0, 0), 1e-12);
  expect_near3(t.type_color[kFoam], Vec3d(0, 0.6, 0), 1e-12);
  expect_near3(s.color, Vec3d(0.4, 0.6, 0), 1e-12);
  const RaySample plain = absorb_intervals(iv, 2, shading, {});
  EXPECT_EQ(plain.color, s.color) << "asking for the split changes nothing else";
}

// Two samples of one pixel: spray with L = 0.5 and white, foam with L = 0.8 and grey 0.5. Averaged:
// L = 0.65; spray's opacity (1 - 0.5) / 2 = 0.25, foam's (1 - 0.8) / 2 = 0.1.
TEST(AbsorptionSplit, APixelsTypeLayersAverageItsSamplesAndSumToItsDiffuseColour) {
  RaySample spray, foam;
  RayTypes spray_t, foam_t;
  spray.transmittance = 0.5, spray.color = Vec3d::Ones(), spray_t.share[kSpray] = 1.0, spray_t.type_color[kSpray] = Vec3d::Ones();
  foam.transmittance = 0.8, foam.color = Vec3d::Constant(0.5), foam_t.share[kFoam] = 1.0,
  foam_t.type_color[kFoam] = Vec3d::Constant(0.5);
  PixelAverage avg(true);
  avg.add(spray, &spray_t), avg.add(foam, &foam_t);
  float l;
  Vec3f cd;
  avg.finish(l, cd);
  EXPECT_NEAR(l, 0.65f, 1e-7f);
  Vec3f p[3];
  float o[3];
  for (size_t k = 0; k < 3; ++k) avg.finish_type(k, p[k], o[k]);
  EXPECT_NEAR(o[kSpray], 0.25f, 1e-7f);
  EXPECT_NEAR(o[kFoam], 0.1f, 1e-7f);
  EXPECT_EQ(o[kBubble], 0.0f);
  EXPECT_NEAR(p[kSpray].x(), 0.25f, 1e-7f);
  EXPECT_NEAR(p[kFoam].x(), 0.05f, 1e-7f);
  // Over the types: the opacity 1 - L and the premultiplied colour (1 - L) C_d.
  EXPECT_NEAR(o[kSpray] + o[kFoam] + o[kBubble], 1.0f - l, 1e-7f);
  EXPECT_NEAR((p[kSpray] + p[kFoam] + p[kBubble]).x(), (1.0f - l) * cd.x(), 1e-6f);
  PixelAverage whole;  // without by_type: no layers
  whole.add(spray, &spray_t);
  whole.finish_type(kSpray, p[0], o[0]);
  EXPECT_EQ(o[0], 0.0f);
}

Camera small_camera(int w, int h) {
  Camera c;
  c.position = Vec3f(0.2f, 0.5f, 3.0f);
  c.target = Vec3f(0, 0, 0);
  c.fov_y_degrees = 35.0f;
  c.width = w, c.height = h;
  return c;
}

// Spheres of all three types, overlapping, rendered with and without the split: the split leaves L
// and C_d as they were, and its parts add up to them.
TEST(AbsorptionSplit, TheVolumePassesPartsAddUpToItsImageAndLeaveItUnchanged) {
  DiffuseFrame f;
  const Vec3f centres[6] = {{0, 0, 0}, {0.15f, 0.05f, 0}, {-0.1f, 0.1f, 0.1f}, {0.05f, -0.1f, -0.1f}, {0.3f, 0, 0}, {-0.3f, -0.1f, 0}};
  f.resize(6);
  for (size_t i = 0; i < 6; ++i) f.positions[i] = centres[i], f.types[i] = DiffuseType(i % 3);
  VolumeSettings s;
  for (auto& l : s.look) l.radius = 0.15f;
  s.look[kSpray].color = Vec3f(1, 0.2f, 0.2f), s.look[kFoam].color = Vec3f(0.2f, 1, 0.2f), s.look[kBubble].color = Vec3f(0.2f, 0.2f, 1);
  s.alpha = 8.0f;
  s.samples_per_pixel = 4;
  const Camera cam = small_camera(48, 32);
  const VolumeImage whole = render_volume(f, cam, s);
  s.split_types = true;
  const VolumeImage split = render_volume(f, cam, s);
  int mixed = 0;
  for (size_t p = 0; p < whole.pixel_count(); ++p) {
    ASSERT_EQ(whole.transmittance[p], split.transmittance[p]);
    ASSERT_EQ(whole.color[p], split.color[p]);
    float opacity = 0.0f;
    Vec3f premultiplied = Vec3f::Zero();
    int types = 0;
    for (size_t k = 0; k < 3; ++k) {
      opacity += split.type_opacity[k][p], premultiplied += split.type_premultiplied[k][p];
      types += split.type_opacity[k][p] > 0.0f;
    }
    mixed += types > 1;
    EXPECT_NEAR(opacity, 1.0f - split.transmittance[p], 1e-6f) << "pixel " << p;
    const Vec3f expected = (1.0f - split.transmittance[p]) * split.color[p];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(premultiplied[c], expected[c], 1e-6f) << "pixel " << p;
  }
  EXPECT_GT(mixed, 20) << "the spheres overlap: some pixels see several types";
}

// A 4 x 1 frame by hand: sky; ground; water over the ground; water over the sky. Diffuse material
// with opacities 0.3 (spray) and 0.2 (foam) over the third pixel.
TEST(FrameLayersTest, EachLayerHoldsItsElementAndTogetherTheyRebuildBeauty) {
  const Camera cam = small_camera(4, 1);
  SurfaceImage surface;
  surface.colour = ImageRGBf(4, 1), surface.opaque_colour = ImageRGBf(4, 1);
  const Vec3f sky(0.5f, 0.6f, 0.9f), ground(0.3f, 0.25f, 0.2f), water(0.05f, 0.2f, 0.3f);
  surface.opaque_colour.rgb = {sky, ground, ground, sky};
  surface.colour.rgb = {sky, ground, water, 0.5f * water};
  surface.opaque_depth = {INFINITY, 4.0f, 5.0f, INFINITY};
  surface.depth = {INFINITY, 4.0f, 3.0f, 6.0f};
  VolumeImage volume;
  volume.width = 4, volume.height = 1;
  volume.transmittance = {1, 1, 0.5f, 1};
  volume.color.assign(4, Vec3f::Zero());
  for (size_t k = 0; k < 3; ++k) volume.type_opacity[k].assign(4, 0.0f), volume.type_premultiplied[k].assign(4, Vec3f::Zero());
  volume.type_opacity[kSpray][2] = 0.3f, volume.type_premultiplied[kSpray][2] = Vec3f(0.3f, 0.3f, 0.3f);
  volume.type_opacity[kFoam][2] = 0.2f, volume.type_premultiplied[kFoam][2] = Vec3f(0.1f, 0.1f, 0.1f);
  volume.color[2] = Vec3f(0.4f, 0.4f, 0.4f) / 0.5f;
  const ImageRGBf beauty = composite(volume, surface.colour);
  const FrameLayers f = frame_layers(beauty, surface, &volume, {true, true, false}, cam);

  ASSERT_EQ(f.layers.size(), 5u) << "sky, opaque, water, spray, foam: bubbles are not drawn";
  const RgbaLayer &sky_l = *f.layer("sky"), &opaque_l = *f.layer("opaque"), &water_l = *f.layer("water");
  EXPECT_EQ(f.layer("bubble"), nullptr);
  const std::vector<float> sky_a = {1, 0, 0, 1}, opaque_a = {0, 1, 1, 0}, water_a = {0, 0, 1, 1};
  for (size_t p = 0; p < 4; ++p) {
    EXPECT_EQ(sky_l.pixels[p][3], sky_a[p]) << p;
    EXPECT_EQ(opaque_l.pixels[p][3], opaque_a[p]) << p;
    EXPECT_EQ(water_l.pixels[p][3], water_a[p]) << p;
  }
  EXPECT_EQ(water_l.pixels[3][2], 0.5f * water.z()) << "the water seen against the sky";
  EXPECT_EQ(opaque_l.pixels[2][0], ground.x()) << "the ground under the water";
  EXPECT_EQ(f.layer("spray")->pixels[2][3], 0.3f);
  EXPECT_EQ(f.layer("foam")->pixels[2][0], 0.1f);
  // Beauty at the diffuse pixel by hand: 0.4 + 0.5 * water.
  EXPECT_NEAR(f.beauty[2][1], 0.4f + 0.5f * water.y(), 1e-6f);
  const std::vector<Rgba> rebuilt = recomposite(f);
  for (size_t p = 0; p < 4; ++p)
    for (size_t c = 0; c < 4; ++c) EXPECT_NEAR(rebuilt[p][c], f.beauty[p][c], 1e-6f) << "pixel " << p << " channel " << c;
  EXPECT_EQ(f.distance[0], FrameLayers::kSkyDistance);
}

// Z is the distance from the camera to the surface along the pixel's ray: for planar depth d it is
// d / cos(angle between the ray and the view axis), taken here from Camera::ray.
TEST(FrameLayersTest, ZIsTheDistanceAlongThePixelsRay) {
  const Camera cam = small_camera(64, 40);
  SurfaceImage surface;
  surface.colour = ImageRGBf(64, 40), surface.opaque_colour = ImageRGBf(64, 40);
  surface.depth.assign(64 * 40, 2.5f);
  surface.opaque_depth = surface.depth;
  const FrameLayers f = frame_layers(surface.colour, surface, nullptr, {false, false, false}, cam);
  Vec3f right, up, back;
  cam.basis(right, up, back);
  for (int y : {0, 17, 39})
    for (int x : {0, 31, 63}) {
      const Ray r = cam.ray(float(x) + 0.5f, float(y) + 0.5f);
      const float expected = 2.5f / r.direction.dot(-back);
      EXPECT_NEAR(f.distance[size_t(y) * 64 + size_t(x)], expected, 1e-5f * expected) << x << "," << y;
    }
  EXPECT_GT(f.distance[0], 2.6f) << "a corner is further than the centre";
}

}  // namespace
}  // namespace spume
