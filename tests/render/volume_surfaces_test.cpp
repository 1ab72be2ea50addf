// Opaque solids end eye rays; the water surface is not opaque but dims what is seen through it by
// exp(-sigma_w * distance travelled in water), leaving L unchanged.
#include <gtest/gtest.h>

#include <cmath>

#include "render/surface/triangle_mesh.h"
#include "render/volume/volume_pass.h"

namespace spume {
namespace {

// A square of half-size h in the plane through `centre` spanned by unit axes a, b; counter-clockwise
// seen from the side a x b points to.
TriangleMesh quad(const Vec3f& centre, const Vec3f& a, const Vec3f& b, float h) {
  TriangleMesh m;
  m.vertices = {centre - h * a - h * b, centre + h * a - h * b, centre + h * a + h * b, centre - h * a + h * b};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

DiffuseFrame one_type(const std::vector<Vec3f>& centres) {
  DiffuseFrame f;
  f.resize(centres.size());
  for (size_t i = 0; i < centres.size(); ++i) f.positions[i] = centres[i], f.types[i] = DiffuseType::Bubble;
  return f;
}

Camera camera(const Vec3f& pos, const Vec3f& target) {
  Camera c;
  c.position = pos, c.target = target, c.fov_y_degrees = 40.0f, c.width = 80, c.height = 60;
  return c;
}

struct Chord {
  double t0 = 0, t1 = 0;
  bool hit = false;
};
Chord chord(const Ray& ray, const Vec3f& centre, double R) {
  const Vec3d o = ray.origin.cast<double>(), d = ray.direction.cast<double>().normalized();
  const Vec3d p = centre.cast<double>() - o;
  const double tc = p.dot(d), b2 = (p - tc * d).squaredNorm();
  if (b2 >= R * R) return {};
  return {tc - std::sqrt(R * R - b2), tc + std::sqrt(R * R - b2), true};
}

VolumeSettings bubbles(float radius, float alpha, VolumeIntegrator integrator = VolumeIntegrator::Exact) {
  VolumeSettings s;
  s.look[size_t(DiffuseType::Bubble)] = {radius, Vec3f::Ones()};
  s.alpha = alpha;
  s.water_sigma = Vec3f(2.0f, 1.0f, 0.25f);
  s.integrator = integrator;
  return s;
}

TEST(VolumeSolids, WallThroughTheSphereCutsTheChord) {
  const Camera cam = camera(Vec3f(0.3f, 0.4f, 3.0f), Vec3f::Zero());
  const float R = 0.4f;
  const double alpha = 3.0;
  const TriangleMesh wall = quad(Vec3f::Zero(), Vec3f::UnitX(), Vec3f::UnitY(), 10.0f);  // z = 0, facing +z
  for (ExactMethod m : {ExactMethod::ScreenBins, ExactMethod::EmbreeAllHits}) {
    VolumeSettings s = bubbles(R, float(alpha));
    s.exact_method = m;
    const VolumeImage img = render_volume(one_type({Vec3f::Zero()}), cam, s, {nullptr, &wall});
    int cut = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const Ray ray = cam.ray(x + 0.5f, y + 0.5f);
        const Chord c = chord(ray, Vec3f::Zero(), R);
        const double t_wall = -double(ray.origin.z()) / double(ray.direction.normalized().z());
        const double len = c.hit ? std::max(0.0, std::min(c.t1, t_wall) - c.t0) : 0.0;
        cut += c.hit && c.t1 > t_wall;
        EXPECT_NEAR(img.transmittance[size_t(y * cam.width + x)], std::exp(-alpha * len), 1e-5) << x << "," << y;
      }
    EXPECT_GT(cut, 100);
  }
}

TEST(VolumeSolids, OccluderInFrontHidesEverythingBehind) {
  const Camera cam = camera(Vec3f(0.0f, 0.0f, 3.0f), Vec3f::Zero());
  const TriangleMesh card = quad(Vec3f(0.0f, 0.0f, 1.0f), Vec3f::UnitX(), Vec3f::UnitY(), 0.12f);
  for (VolumeIntegrator integ : {VolumeIntegrator::Exact, VolumeIntegrator::March}) {
    const VolumeImage img = render_volume(one_type({Vec3f::Zero()}), cam, bubbles(0.4f, 5.0f, integ), {nullptr, &card});
    int hidden = 0, seen = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const Ray ray = cam.ray(x + 0.5f, y + 0.5f);
        const float t = (1.0f - ray.origin.z()) / ray.direction.z();
        const Vec3f p = ray.origin + t * ray.direction;
        const float L = img.transmittance[size_t(y * cam.width + x)];
        if (std::abs(p.x()) < 0.119f && std::abs(p.y()) < 0.119f) {
          EXPECT_EQ(L, 1.0f) << x << "," << y;
          ++hidden;
        } else if (chord(ray, Vec3f::Zero(), 0.4).hit && std::abs(p.x()) > 0.121f) {
          seen += L < 0.99f;
        }
      }
    EXPECT_GT(hidden, 20);
    EXPECT_GT(seen, 100);
  }
}

// Integral over [t0, t1] of the dimming exp(-sigma * w(t)) for a ray dry before t_w and in water
// after it, by Simpson's rule (2000 panels), independent of the pass's closed form.
double dimmed(double t0, double t1, double t_w, double sigma) {
  auto D = [&](double t) { return std::exp(-sigma * std::max(0.0, t - t_w)); };
  double simpson = 0.0;
  const int n = 2000;
  const double h = (t1 - t0) / n;
  for (int i = 0; i <= n; ++i) simpson += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * D(t0 + i * h);
  return simpson * h / 3.0;
}

TEST(VolumeWater, SubmergedBubblesAreDimmedByTheWaterPath) {
  const Camera cam = camera(Vec3f(0.0f, 1.5f, 2.5f), Vec3f(0.0f, -0.4f, 0.0f));
  const TriangleMesh water = quad(Vec3f::Zero(), Vec3f::UnitZ(), Vec3f::UnitX(), 10.0f);  // y = 0, normal +y
  const Vec3f below(0.0f, -0.4f, 0.0f), above(0.6f, 0.4f, 0.0f);
  const float Rb = 0.25f, Ra = 0.2f;
  // Different radii need different types: the bubble is under water, the foam ball above it.
  DiffuseFrame f = one_type({below, above});
  f.types[1] = DiffuseType::Foam;
  VolumeSettings s = bubbles(Rb, 2.0f);
  s.look[size_t(DiffuseType::Foam)] = {Ra, Vec3f::Ones()};
  const VolumeImage img = render_volume(f, cam, s, {&water, nullptr});
  int dimmed_px = 0, clear_px = 0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const Ray ray = cam.ray(x + 0.5f, y + 0.5f);
      const Chord cb = chord(ray, below, Rb), ca = chord(ray, above, Ra);
      if (cb.hit == ca.hit) continue;  // neither, or both (not checked here)
      const size_t p = size_t(y * cam.width + x);
      const Chord c = cb.hit ? cb : ca;
      const double len = c.t1 - c.t0, t_w = -double(ray.origin.y()) / double(ray.direction.normalized().y());
      EXPECT_NEAR(img.transmittance[p], std::exp(-2.0 * len), 1e-5);  // opacity unchanged by water
      for (int ch = 0; ch < 3; ++ch)
        EXPECT_NEAR(img.color[p][ch], dimmed(c.t0, c.t1, t_w, s.water_sigma[ch]) / len, 2e-5) << x << "," << y;
      if (cb.hit) {
        ++dimmed_px;
        // Fully under water: exp(-sigma (t0 - t_w)) (1 - exp(-sigma len)) / (sigma len), by hand.
        const double sg = s.water_sigma[0];
        EXPECT_NEAR(img.color[p][0], std::exp(-sg * (c.t0 - t_w)) * (1 - std::exp(-sg * len)) / (sg * len), 2e-5);
      } else {
        ++clear_px;
        EXPECT_NEAR(img.color[p][0], 1.0f, 1e-6f);
      }
    }
  EXPECT_GT(dimmed_px, 100);
  EXPECT_GT(clear_px, 30);
}

// A water surface folded along a ridge into a steep V (water below it): two triangles that Embree gets
// as one quad. A ray entering through one wing would be taken for one leaving through the other wing's
// normal, so each crossing must be judged by the wing it went through. Mirrored, the camera looks
// through each wing in turn.
TEST(VolumeWater, EachWingOfAFoldedSurfaceDimsWhatIsBelowIt) {
  for (float side : {1.0f, -1.0f}) {
    // Ridge along z through the origin; the wings rise to x = -+5, y = 10 (planes y = -+2x).
    TriangleMesh water;
    water.vertices = {Vec3f(0, 0, -10), Vec3f(0, 0, 10), Vec3f(-5, 10, 0), Vec3f(5, 10, 0)};
    water.indices = {1, 0, 2,   // left wing, normal along (2, 1, 0)
                     0, 1, 3};  // right wing, normal along (-2, 1, 0)
    const Vec3f n_far = Vec3f(2.0f * side, 1.0f, 0.0f).normalized();  // the wing the camera looks through
    const Vec3f bubble(-3.0f * side, 2.0f, 0.0f);  // under it, 1.79 m from its plane
    const Camera cam = camera(Vec3f(3.0f * side, 9.0f, 3.0f), bubble);
    VolumeSettings s = bubbles(0.8f, 2.0f);
    const VolumeImage img = render_volume(one_type({bubble}), cam, s, {&water, nullptr});
    int n = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const Ray ray = cam.ray(x + 0.5f, y + 0.5f);
        const Chord c = chord(ray, bubble, 0.8);
        if (!c.hit) continue;
        ++n;
        // Into the water through the far wing's plane, which holds the origin.
        const Vec3d o = ray.origin.cast<double>(), d = ray.direction.cast<double>().normalized();
        const double t_w = -o.dot(n_far.cast<double>()) / d.dot(n_far.cast<double>());
        ASSERT_GT(t_w, 0.0);
        ASSERT_LT(t_w, c.t0);
        for (int ch = 0; ch < 3; ++ch)
          EXPECT_NEAR(img.color[size_t(y * cam.width + x)][ch], dimmed(c.t0, c.t1, t_w, s.water_sigma[ch]) / (c.t1 - c.t0), 2e-5)
              << "side " << side << " pixel " << x << "," << y;
      }
    EXPECT_GT(n, 100);
  }
}

TEST(VolumeWater, CameraUnderWaterLooksOut) {
  const Camera cam = camera(Vec3f(0.0f, -1.0f, 2.0f), Vec3f(0.0f, 0.5f, 0.0f));
  const TriangleMesh water = quad(Vec3f::Zero(), Vec3f::UnitZ(), Vec3f::UnitX(), 10.0f);
  const Vec3f centre(0.0f, 0.5f, 0.0f);
  for (VolumeIntegrator integ : {VolumeIntegrator::Exact, VolumeIntegrator::March}) {
    VolumeSettings s = bubbles(0.2f, 2.0f, integ);
    s.march_step = 1e-4f;
    const VolumeImage img = render_volume(one_type({centre}), cam, s, {&water, nullptr});
    int n = 0;
    for (int y = 0; y < cam.height; ++y)
      for (int x = 0; x < cam.width; ++x) {
        const Ray ray = cam.ray(x + 0.5f, y + 0.5f);
        const Chord c = chord(ray, centre, 0.2);
        if (!c.hit || c.t1 - c.t0 < 0.05) continue;
        ++n;
        // The whole way to the surface is water: every channel dimmed by exp(-sigma t_w).
        const double t_w = -double(ray.origin.y()) / double(ray.direction.normalized().y());
        const double tol = integ == VolumeIntegrator::Exact ? 1e-5 : 2e-3;
        for (int ch = 0; ch < 3; ++ch)
          EXPECT_NEAR(img.color[size_t(y * cam.width + x)][ch], std::exp(-s.water_sigma[ch] * t_w), tol);
      }
    EXPECT_GT(n, 100);
  }
}

}  // namespace
}  // namespace spume
