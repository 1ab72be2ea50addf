// Motion blur of the diffuse material (volume/swept_*.h): each particle's chord averaged over its path
// during the shutter, checked against brute-force averages over many instants, against the streak a
// particle crossing the screen must leave, and against the still picture.
#include <gtest/gtest.h>

#include <cmath>

#include "render/volume/swept_absorption.h"
#include "render/volume/swept_sphere.h"
#include "render/volume/volume_pass.h"
#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {
namespace {

// The chord of a sphere at c (radius^2 r2) along the ray o + s d, |d| = 1; [lo, hi] of it.
double chord(const Vec3d& c, double r2, const Vec3d& o, const Vec3d& d, double* lo = nullptr, double* hi = nullptr) {
  const Vec3d q = c - o;
  const double tc = q.dot(d), b2 = q.squaredNorm() - tc * tc;
  if (b2 >= r2) return 0.0;
  const double h = std::sqrt(r2 - b2);
  if (lo) *lo = tc - h, *hi = tc + h;
  return 2.0 * h;
}

// The piece's time-averaged chord and support, by 200k instants.
TEST(SweptSphere, ClosedFormChordAveragesWhatManyInstantsGive) {
  const Vec3d o(0.1, -0.2, 3.0), d = Vec3d(-0.05, 0.08, -1.0).normalized();
  const double r2 = 0.2 * 0.2;
  const PathPiece cases[] = {{Vec3d(-0.3, 0.1, 0.0), Vec3d(0.6, -0.35, 0.2), 0.0, 1.0},   // across the ray
                             {Vec3d(0.05, -0.1, 0.4), Vec3d(0.0, 0.0, -0.9), 0.25, 0.5},  // along it, a quarter of a shutter
                             {Vec3d(0.0, 0.1, 0.0), Vec3d(0.05, 0.01, 0.0), 0.0, 1.0}};   // slow
  for (const PathPiece& p : cases) {
    SweptChord c;
    ASSERT_TRUE(swept_chord(p, r2, o, d, c));
    const int n = 200000;
    double sum = 0.0, lo = INFINITY, hi = -INFINITY;
    for (int i = 0; i < n; ++i) {
      double a, b;
      const double len = chord(p.a + ((i + 0.5) / n) * p.b, r2, o, d, &a, &b);
      sum += len;
      if (len > 0.0) lo = std::min(lo, a), hi = std::max(hi, b);
    }
    EXPECT_NEAR(c.area, p.w * sum / n, 1e-5 * c.area) << "piece moving by " << p.b.transpose();
    EXPECT_NEAR(c.s_lo, lo, 1e-5);  // the instants' ends come within sqrt(1 / n) of a square-root edge
    EXPECT_NEAR(c.s_hi, hi, 1e-5);
  }
  SweptChord c;
  EXPECT_FALSE(swept_chord({Vec3d(1.0, 0.0, 0.0), Vec3d(0.5, 0.0, 0.0), 0.0, 1.0}, r2, o, d, c)) << "never near the ray";
}

TEST(SweptSphere, SprayFollowsItsParabolaInPiecesTheOthersAStraightLine) {
  const Vec3d c(1, 2, 3), v(4, 5, -6), g(0, -9.81, 0);
  std::array<PathPiece, kSprayPieces> p;
  ASSERT_EQ(path_pieces(c, v, DiffuseType::Spray, -0.01, 0.01, g, p), kSprayPieces);
  double share = 0.0;
  for (int k = 0; k < kSprayPieces; ++k) {
    const double t = -0.01 + 0.02 * k / kSprayPieces, t1 = t + 0.02 / kSprayPieces;
    const Vec3d start = c + t * v + 0.5 * t * t * g, end = c + t1 * v + 0.5 * t1 * t1 * g;
    EXPECT_LT((p[size_t(k)].a - start).norm(), 1e-12);
    EXPECT_LT((p[size_t(k)].a + p[size_t(k)].b - end).norm(), 1e-12);
    EXPECT_NEAR(p[size_t(k)].t0, share, 1e-15);
    share += p[size_t(k)].w;
  }
  EXPECT_NEAR(share, 1.0, 1e-15);
  ASSERT_EQ(path_pieces(c, v, DiffuseType::Foam, -0.01, 0.01, g, p), 1);
  EXPECT_LT((p[0].a - (c - 0.01 * v)).norm(), 1e-12);
  EXPECT_LT((p[0].b - 0.02 * v).norm(), 1e-12);
  // The most a parabola strays from a chord of it spanning T is g T^2 / 8.
  EXPECT_NEAR(path_sag(-0.01, 0.01, g), 9.81 * 0.005 * 0.005 / 8.0, 1e-15);
}

// Spheres at rest give Eq. 9's union of chords; one moving alone keeps its whole area.
TEST(SweptAbsorption, AtRestItIsTheUnionAloneItIsTheAverage) {
  VolumeShading shading;
  shading.alpha = 2.0;
  for (auto& c : shading.color) c = Vec3d::Ones();
  SweptScratch scratch;
  // Two spheres at rest overlapping along the ray: [1, 3] and [2, 5] -> union 4.
  std::vector<SweptChord> rest = {{1.0, 3.0, 2.0, 1, 0}, {2.0, 5.0, 3.0, 1, 1}};
  EXPECT_NEAR(absorb_swept(rest, 0.0, 10.0, shading, {}, scratch).transmittance, std::exp(-2.0 * 4.0), 1e-12);
  // One particle smeared over [1, 5] with an average chord of 0.8 (two pieces: 0.3 + 0.5).
  std::vector<SweptChord> moving = {{1.0, 3.5, 0.3, 0, 7}, {2.5, 5.0, 0.5, 0, 7}};
  EXPECT_NEAR(absorb_swept(moving, 0.0, 10.0, shading, {}, scratch).transmittance, std::exp(-2.0 * 0.8), 1e-12);
  // The ray ends at 3 (an opaque solid): the density 0.8 / 4 is kept over [1, 3].
  EXPECT_NEAR(absorb_swept(moving, 0.0, 3.0, shading, {}, scratch).transmittance, std::exp(-2.0 * 0.2 * 2.0), 1e-12);
}

Camera front_camera(int width = 240, int height = 120) {
  Camera c;
  c.position = Vec3d(0, 0, 2).cast<float>();
  c.target = Vec3f(0, 0, 0);
  c.fov_y_degrees = 30.0f;
  c.width = width, c.height = height;
  return c;
}

struct Streak {
  int x0 = 1 << 30, x1 = -1, y0 = 1 << 30, y1 = -1;
  double optical_depth = 0.0;  // sum over pixels of -ln L
};

Streak measure(const VolumeImage& img) {
  Streak s;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const float l = img.transmittance[size_t(y) * size_t(img.width) + size_t(x)];
      if (l >= 1.0f) continue;
      s.x0 = std::min(s.x0, x), s.x1 = std::max(s.x1, x), s.y0 = std::min(s.y0, y), s.y1 = std::max(s.y1, y);
      s.optical_depth -= std::log(double(l));
    }
  return s;
}

// A foam particle crossing the screen at 3 m/s with a half-frame shutter at 25 fps: it moves
// 3 * 0.5 / 25 = 0.06 m while the shutter is open. At 2 m with a 30-degree field over 240 pixels,
// a metre is 240 / (2 * 2 tan 15 deg) = 223.9 pixels: the streak is 0.06 m + the diameter long. One
// ray a pixel, so -ln L is each pixel centre's optical depth, and their sum the integral over the image.
TEST(MotionBlur, AParticleCrossingTheScreenLeavesAStreakOfItsPathWithItsOpticalDepth) {
  DiffuseFrame f;
  f.resize(1);
  f.positions[0] = Vec3f(0.0f, 0.0f, 0.0f), f.types[0] = DiffuseType::Foam;
  const std::vector<Vec3f> velocity = {Vec3f(3.0f, 0.0f, 0.0f)};
  VolumeSettings s;
  for (auto& l : s.look) l.radius = 0.05f;
  s.alpha = 20.0f;
  const Camera cam = front_camera(480, 240);
  const Streak still = measure(render_volume(f, cam, s));
  s.shutter = 0.5f, s.frame_seconds = 1.0 / 25.0;
  const Streak blurred = measure(render_volume(f, cam, s, {}, nullptr, velocity));
  const double px_per_m = 240.0 / (2.0 * 2.0 * std::tan(15.0 * M_PI / 180.0));
  EXPECT_NEAR(still.x1 - still.x0 + 1, 0.1 * px_per_m, 1.5);
  EXPECT_NEAR(blurred.x1 - blurred.x0 + 1, (0.06 + 0.1) * px_per_m, 1.5) << "streak length in pixels";
  EXPECT_EQ(blurred.y1 - blurred.y0, still.y1 - still.y0) << "a horizontal streak keeps its height";
  // The same absorption spread over more pixels (perspective changes a sphere's footprint by under
  // 0.1% at these angles).
  EXPECT_NEAR(blurred.optical_depth, still.optical_depth, 0.01 * still.optical_depth);
  EXPECT_LT(blurred.optical_depth / (blurred.x1 - blurred.x0 + 1), 0.7 * still.optical_depth / (still.x1 - still.x0 + 1))
      << "and thinner per pixel";
}

// Spray falls while the shutter is open: its streak bends down by the parabola's sag, and its ends
// are where c + v t + g t^2 / 2 puts them.
TEST(MotionBlur, SprayStreaksFollowTheirBallisticPath) {
  DiffuseFrame f;
  f.resize(1);
  f.positions[0] = Vec3f(0.0f, 0.1f, 0.0f), f.types[0] = DiffuseType::Spray;
  const std::vector<Vec3f> velocity = {Vec3f(0.0f, -4.0f, 0.0f)};  // falling through the image
  VolumeSettings s;
  for (auto& l : s.look) l.radius = 0.01f;
  s.alpha = 50.0f, s.samples_per_pixel = 16, s.shutter = 1.0f, s.frame_seconds = 1.0 / 10.0, s.gravity = Vec3f(0, -9.81f, 0);
  const Camera cam = front_camera();
  const Streak st = measure(render_volume(f, cam, s, {}, nullptr, velocity));
  // Over t in [-0.05, 0.05]: y = 0.1 - 4 t - 4.905 t^2 runs from 0.2 - 0.0123 to 0.0 - 0.0123.
  const double px_per_m = 120.0 / (2.0 * 2.0 * std::tan(15.0 * M_PI / 180.0));
  const double top = 0.1 + 0.2 - 4.905 * 0.0025 + 0.01, bottom = 0.1 - 0.2 - 4.905 * 0.0025 - 0.01;
  EXPECT_NEAR(st.y0, 60.0 - top * px_per_m, 1.5);
  EXPECT_NEAR(st.y1, 60.0 - bottom * px_per_m, 1.5);
}

TEST(MotionBlur, TheImageDoesNotDependOnTheThreadCount) {
  DiffuseFrame f;
  f.resize(300);
  std::vector<Vec3f> velocity(300);
  for (size_t i = 0; i < 300; ++i) {
    const float a = float(i) * 0.37f;
    f.positions[i] = Vec3f(0.3f * std::sin(a), 0.2f * std::cos(1.3f * a), 0.1f * std::sin(2.1f * a));
    f.types[i] = DiffuseType(i % 3);
    velocity[i] = Vec3f(2.0f * std::cos(a), 1.5f * std::sin(0.7f * a), -1.0f);
  }
  VolumeSettings s;
  for (auto& l : s.look) l.radius = 0.03f;
  s.samples_per_pixel = 4, s.shutter = 0.5f, s.frame_seconds = 1.0 / 24.0, s.split_types = true;
  set_thread_count(1);
  const VolumeImage one = render_volume(f, front_camera(), s, {}, nullptr, velocity);
  set_thread_count(2);
  const VolumeImage two = render_volume(f, front_camera(), s, {}, nullptr, velocity);
  set_thread_count(0);
  EXPECT_EQ(one.transmittance, two.transmittance);
  EXPECT_EQ(one.color, two.color);
  EXPECT_EQ(one.type_opacity, two.type_opacity);
  EXPECT_LT(*std::min_element(one.transmittance.begin(), one.transmittance.end()), 0.9f) << "something was drawn";
}

TEST(MotionBlur, NeedsAVelocityPerParticle) {
  DiffuseFrame f;
  f.resize(2);
  VolumeSettings s;
  for (auto& l : s.look) l.radius = 0.03f;
  s.shutter = 0.5f, s.frame_seconds = 0.04;
  const std::vector<Vec3f> one = {Vec3f::Zero()};
  EXPECT_THROW(render_volume(f, front_camera(), s, {}, nullptr, one), Error);
}

}  // namespace
}  // namespace spume
