// The exact integrator against chords worked out independently: L = exp(-alpha * length inside the
// union of spheres), lengths from 2 sqrt(R^2 - b^2) with the impact parameter b of each pixel ray.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/core/error.h"
#include "render/volume/composite.h"
#include "render/volume/volume_pass.h"

namespace spume {
namespace {

Camera test_camera(int w = 70, int h = 45) {
  Camera c;
  c.position = Vec3f(0.3f, 0.4f, 3.0f);
  c.target = Vec3f(0.0f, 0.0f, 0.0f);
  c.fov_y_degrees = 30.0f;
  c.width = w, c.height = h;
  return c;
}

struct Ball {
  Vec3f c;
  DiffuseType type = DiffuseType::Foam;
};

DiffuseFrame frame_of(const std::vector<Ball>& balls) {
  DiffuseFrame f;
  f.resize(balls.size());
  for (size_t i = 0; i < balls.size(); ++i) f.positions[i] = balls[i].c, f.types[i] = balls[i].type;
  return f;
}

VolumeSettings exact_settings(float radius, float alpha, ExactMethod method) {
  VolumeSettings s;
  for (auto& l : s.look) l.radius = radius;
  s.alpha = alpha;
  s.integrator = VolumeIntegrator::Exact;
  s.exact_method = method;
  return s;
}

// Independent reference: the pixel-centre ray in double, chords from the perpendicular vector,
// union by sorting and merging.
double union_length(const Camera& cam, int x, int y, const std::vector<Ball>& balls, double R) {
  const Ray ray = cam.ray(float(x) + 0.5f, float(y) + 0.5f);
  const Vec3d o = ray.origin.cast<double>(), d = ray.direction.cast<double>().normalized();
  std::vector<std::pair<double, double>> iv;
  for (const Ball& b : balls) {
    const Vec3d p = b.c.cast<double>() - o;
    const double tc = p.dot(d), b2 = (p - tc * d).squaredNorm();
    if (b2 < R * R) iv.push_back({tc - std::sqrt(R * R - b2), tc + std::sqrt(R * R - b2)});
  }
  std::sort(iv.begin(), iv.end());
  double len = 0.0, s = -INFINITY, e = -INFINITY;
  for (auto [a, b] : iv) {
    if (a > e) {
      if (e > s) len += e - s;
      s = a, e = b;
    } else e = std::max(e, b);
  }
  if (e > s) len += e - s;
  return len;
}

class VolumeExact : public ::testing::TestWithParam<ExactMethod> {};

TEST_P(VolumeExact, SingleSphereIsExpOfChord) {
  const Camera cam = test_camera();
  const std::vector<Ball> balls = {{Vec3f(0.05f, -0.02f, 0.1f)}};
  const double R = 0.4, alpha = 3.0;
  const VolumeImage img = render_volume(frame_of(balls), cam, exact_settings(float(R), float(alpha), GetParam()));
  int inside = 0;
  double worst = 0.0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const double len = union_length(cam, x, y, balls, R);
      inside += len > 0.0;
      worst = std::max(worst, std::abs(img.transmittance[size_t(y * cam.width + x)] - std::exp(-alpha * len)));
    }
  EXPECT_LT(worst, 1e-5);
  EXPECT_GT(inside, 200);
  EXPECT_LT(inside, cam.width * cam.height - 200);
}

TEST_P(VolumeExact, OverlappingSlabIsUnionNotSum) {
  const Camera cam = test_camera();
  const double R = 0.1, alpha = 4.0;
  std::vector<Ball> balls;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 2; ++k)  // spacing 0.15 < 2R: neighbours overlap
        balls.push_back({Vec3f(-0.5f + 0.15f * float(i), -0.5f + 0.15f * float(j), 0.15f * float(k)),
                         (i + j) % 2 ? DiffuseType::Spray : DiffuseType::Foam});
  const VolumeImage img = render_volume(frame_of(balls), cam, exact_settings(float(R), float(alpha), GetParam()));
  double worst = 0.0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x)
      worst = std::max(worst, std::abs(img.transmittance[size_t(y * cam.width + x)] - std::exp(-alpha * union_length(cam, x, y, balls, R))));
  EXPECT_LT(worst, 1e-5);
}

// Spheres placed on one pixel's ray: lengths by hand.
TEST_P(VolumeExact, SpheresOnOneRayByHand) {
  const Camera cam = test_camera();
  const int px = 33, py = 20;
  const Ray ray = cam.ray(px + 0.5f, py + 0.5f);
  const float R = 0.1f;
  auto at = [&](float t) { return Ball{ray.origin + t * ray.direction}; };
  const double alpha = 2.0;
  auto L = [&](const std::vector<Ball>& balls) {
    return render_volume(frame_of(balls), cam, exact_settings(R, float(alpha), GetParam())).transmittance[size_t(py * cam.width + px)];
  };
  // Overlapping pair (centres 1.5R apart) and a separate one: (2R + 1.5R) + 2R = 5.5R.
  EXPECT_NEAR(L({at(2.5f), at(2.5f + 1.5f * R), at(2.5f + 5.0f * R)}), std::exp(-alpha * 5.5 * R), 1e-5);
  // Touching spheres (centres exactly 2R apart: the exit and entry events share one t): 4R.
  EXPECT_NEAR(L({at(2.5f), at(2.5f + 2.0f * R)}), std::exp(-alpha * 4.0 * R), 1e-5);
  // A duplicated particle (bit-identical events) counts once: 2R.
  EXPECT_NEAR(L({at(2.5f), at(2.5f)}), std::exp(-alpha * 2.0 * R), 1e-5);
  // One sphere inside another: the larger chord only.
  EXPECT_NEAR(L({at(2.5f), at(2.5f + 0.5f * R), at(2.5f - 0.5f * R)}), std::exp(-alpha * 3.0 * R), 1e-5);
}

TEST_P(VolumeExact, TangentRaySeesNothing) {
  const Camera cam = test_camera();
  const int px = 40, py = 12;
  const Ray ray = cam.ray(px + 0.5f, py + 0.5f);
  Vec3f right, up, back;
  cam.basis(right, up, back);
  const Vec3f side = ray.direction.cross(up).normalized();
  const float R = 0.1f;
  const std::vector<Ball> balls = {{ray.origin + 2.5f * ray.direction + R * side}};
  const VolumeImage img = render_volume(frame_of(balls), cam, exact_settings(R, 5.0f, GetParam()));
  EXPECT_NEAR(img.transmittance[size_t(py * cam.width + px)], 1.0, 1e-5);
}

INSTANTIATE_TEST_SUITE_P(Volume, VolumeExact, ::testing::Values(ExactMethod::ScreenBins, ExactMethod::EmbreeAllHits),
                         [](const auto& param_info) { return param_info.param == ExactMethod::ScreenBins ? "ScreenBins" : "EmbreeAllHits"; });

TEST(VolumeComposite, Eq9AtZeroAndOneTransmittance) {
  const Vec3f cd(0.9f, 0.8f, 0.7f), cb(0.1f, 0.2f, 0.3f);
  EXPECT_EQ(composite(0.0f, cd, cb), cd);
  EXPECT_EQ(composite(1.0f, cd, cb), cb);
  EXPECT_TRUE(composite(0.25f, cd, cb).isApprox(0.75f * cd + 0.25f * cb));

  // Rendered: an opaque (alpha huge) sphere gives pure C_d where hit, pure C_b elsewhere.
  const Camera cam = test_camera(32, 24);
  VolumeSettings s = exact_settings(0.0f, 1e6f, ExactMethod::ScreenBins);
  s.look[size_t(DiffuseType::Foam)] = {0.3f, cd};
  const VolumeImage img = render_volume(frame_of({{Vec3f::Zero()}}), cam, s);
  const ImageRGBf out = composite(img, cb);
  const ImageRGBf back(cam.width, cam.height, cb);
  EXPECT_EQ(composite(img, back).rgb, out.rgb);
  // Pixel (16, 12) looks at the sphere; (0, 0) misses it.
  EXPECT_EQ(img.transmittance[12 * 32 + 16], 0.0f);
  EXPECT_TRUE(out.at(16, 12).isApprox(cd, 1e-6f));
  EXPECT_EQ(img.transmittance[0], 1.0f);
  EXPECT_EQ(out.at(0, 0), cb);
}

TEST(VolumeComposite, MixedTypesAreOpticalDepthWeighted) {
  const Camera cam = test_camera();
  const int px = 30, py = 25;
  const Ray ray = cam.ray(px + 0.5f, py + 0.5f);
  VolumeSettings s = exact_settings(0.0f, 1.0f, ExactMethod::ScreenBins);
  const Vec3f spray(1.0f, 0.0f, 0.0f), foam(0.0f, 0.0f, 1.0f);
  s.look[size_t(DiffuseType::Spray)] = {0.05f, spray};  // chord 0.1 m
  s.look[size_t(DiffuseType::Foam)] = {0.15f, foam};    // chord 0.3 m
  const DiffuseFrame f = frame_of({{ray.origin + 2.4f * ray.direction, DiffuseType::Spray},
                                   {ray.origin + 2.8f * ray.direction, DiffuseType::Foam}});
  const VolumeImage img = render_volume(f, cam, s);
  const size_t p = size_t(py * cam.width + px);
  EXPECT_NEAR(img.transmittance[p], std::exp(-0.4), 1e-5);
  EXPECT_TRUE(img.color[p].isApprox((0.1f * spray + 0.3f * foam) / 0.4f, 1e-5f)) << img.color[p].transpose();
}

TEST(VolumeSkip, UndrawnTypesBuildNothing) {
  const Camera cam = test_camera(20, 10);
  VolumeSettings s;
  s.look[size_t(DiffuseType::Spray)].radius = 0.2f;  // only spray is drawn
  const DiffuseFrame foam_only = frame_of({{Vec3f::Zero(), DiffuseType::Foam}});
  EXPECT_FALSE(volume_pass_needed(foam_only, s));
  VolumeStats st;
  const VolumeImage img = render_volume(foam_only, cam, s, {}, &st);
  EXPECT_TRUE(st.skipped);
  EXPECT_EQ(st.spheres, 0u);
  EXPECT_EQ(img.transmittance, std::vector<float>(200, 1.0f));
  // A drawn type next to an undrawn one: only its sphere counts.
  const DiffuseFrame both = frame_of({{Vec3f::Zero(), DiffuseType::Foam}, {Vec3f(5, 5, 5), DiffuseType::Spray}});
  render_volume(both, cam, s, {}, &st);
  EXPECT_FALSE(st.skipped);
  EXPECT_EQ(st.spheres, 1u);
  s.look[size_t(DiffuseType::Spray)].radius = -1.0f;
  EXPECT_THROW(render_volume(both, cam, s), Error);
}

}  // namespace
}  // namespace spume

namespace spume {
namespace {

// A camera inside a sphere sees the chord from itself to the exit: length R from the centre.
TEST(VolumeInside, CameraAtTheCentreOfASphere) {
  Camera cam = test_camera(40, 30);
  cam.position = Vec3f(0.1f, 0.2f, 0.3f);
  const float R = 0.25f;
  for (VolumeIntegrator integ : {VolumeIntegrator::Exact, VolumeIntegrator::March})
    for (ExactMethod m : {ExactMethod::ScreenBins, ExactMethod::EmbreeAllHits}) {
      VolumeSettings s = exact_settings(R, 2.0f, m);
      s.integrator = integ;
      s.march_step = 1e-5f;
      const VolumeImage img = render_volume(frame_of({{cam.position}}), cam, s);
      const double tol = integ == VolumeIntegrator::Exact ? 1e-5 : 1e-4;
      for (float L : img.transmittance) ASSERT_NEAR(L, std::exp(-2.0 * R), tol);
    }
}

TEST(VolumeInside, BadInputsAreErrors) {
  const Camera cam = test_camera(8, 8);
  DiffuseFrame f = frame_of({{Vec3f::Zero()}});
  f.types[0] = DiffuseType(7);
  EXPECT_THROW(render_volume(f, cam, exact_settings(0.1f, 1.0f, ExactMethod::ScreenBins)), Error);
  f = frame_of({{Vec3f(NAN, 0, 0)}});
  EXPECT_THROW(render_volume(f, cam, exact_settings(0.1f, 1.0f, ExactMethod::ScreenBins)), Error);
  VolumeSettings s = exact_settings(0.1f, 1.0f, ExactMethod::ScreenBins);
  s.samples_per_pixel = 0;
  EXPECT_THROW(render_volume(frame_of({{Vec3f::Zero()}}), cam, s), Error);
}

}  // namespace
}  // namespace spume
