// The volume pass gives the same bytes for any thread count, and its two exact methods agree.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "sim/core/parallel.h"
#include "render/surface/triangle_mesh.h"
#include "render/volume/volume_pass.h"

namespace spume {
namespace {

struct Scene {
  DiffuseFrame frame;
  Camera cam;
  TriangleMesh water, solids;
};

// 20k particles of all three types around a water plane, a solid block partly in front.
Scene busy_scene() {
  Scene s;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  s.frame.resize(20000);
  for (size_t i = 0; i < s.frame.size(); ++i) {
    s.frame.positions[i] = Vec3f(u(rng), 0.4f * u(rng), u(rng));
    s.frame.types[i] = DiffuseType(i % 3);
  }
  s.frame.index = 17;
  s.cam.position = Vec3f(0.5f, 1.2f, 3.0f), s.cam.target = Vec3f(0, -0.1f, 0);
  s.cam.width = 150, s.cam.height = 100;  // partial tiles on both axes
  s.water.vertices = {{-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}};
  s.water.indices = {0, 1, 2, 0, 2, 3};
  s.solids.vertices = {{-0.3f, -1, 0.8f}, {0.2f, -1, 0.8f}, {0.2f, 0.5f, 0.8f}, {-0.3f, 0.5f, 0.8f}};
  s.solids.indices = {0, 1, 2, 0, 2, 3};
  return s;
}

VolumeSettings settings(VolumeIntegrator integ, ExactMethod method) {
  VolumeSettings v;
  v.look[0] = {0.015f, Vec3f(1.0f, 1.0f, 1.0f)};
  v.look[1] = {0.03f, Vec3f(0.9f, 0.95f, 1.0f)};
  v.look[2] = {0.02f, Vec3f(0.7f, 0.8f, 0.9f)};
  v.alpha = 30.0f;
  v.integrator = integ, v.exact_method = method;
  v.march_step = 0.01f;
  v.samples_per_pixel = 3;
  v.seed = 99;
  return v;
}

bool same_bytes(const VolumeImage& a, const VolumeImage& b) {
  return a.transmittance.size() == b.transmittance.size() && a.color.size() == b.color.size() &&
         std::memcmp(a.transmittance.data(), b.transmittance.data(), a.transmittance.size() * sizeof(float)) == 0 &&
         std::memcmp(a.color.data(), b.color.data(), a.color.size() * sizeof(Vec3f)) == 0;
}

TEST(VolumeDeterminism, SameBytesForOneAndTwoThreads) {
  const Scene sc = busy_scene();
  const VolumeSurfaces surf{&sc.water, &sc.solids};
  for (auto [integ, method] : {std::pair{VolumeIntegrator::Exact, ExactMethod::ScreenBins},
                               std::pair{VolumeIntegrator::Exact, ExactMethod::EmbreeAllHits},
                               std::pair{VolumeIntegrator::March, ExactMethod::ScreenBins}}) {
    set_thread_count(1);
    const VolumeImage one = render_volume(sc.frame, sc.cam, settings(integ, method), surf);
    set_thread_count(2);
    const VolumeImage two = render_volume(sc.frame, sc.cam, settings(integ, method), surf);
    EXPECT_TRUE(same_bytes(one, two)) << int(integ) << " " << int(method);
    // Visible material, so the comparison means something.
    size_t opaque = 0;
    for (float L : one.transmittance) opaque += L < 0.5f;
    EXPECT_GT(opaque, one.pixel_count() / 10);
  }
  set_thread_count(0);
}

TEST(VolumeDeterminism, ExactMethodsAgree) {
  const Scene sc = busy_scene();
  const VolumeSurfaces surf{&sc.water, &sc.solids};
  const VolumeImage bins = render_volume(sc.frame, sc.cam, settings(VolumeIntegrator::Exact, ExactMethod::ScreenBins), surf);
  const VolumeImage hits = render_volume(sc.frame, sc.cam, settings(VolumeIntegrator::Exact, ExactMethod::EmbreeAllHits), surf);
  double worst_l = 0.0, worst_c = 0.0;
  for (size_t i = 0; i < bins.pixel_count(); ++i) {
    worst_l = std::max(worst_l, double(std::abs(bins.transmittance[i] - hits.transmittance[i])));
    if (bins.transmittance[i] < 0.999f) worst_c = std::max(worst_c, double((bins.color[i] - hits.color[i]).cwiseAbs().maxCoeff()));
  }
  EXPECT_LT(worst_l, 1e-5);
  EXPECT_LT(worst_c, 1e-4);
}

// Camera inside a cloud: spheres behind it, beside it, straddling its plane and containing it
// exercise the screen bins' culling and whole-image cases; Embree has no such special cases.
TEST(VolumeDeterminism, ExactMethodsAgreeInsideACloud) {
  DiffuseFrame f;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.6f, 0.6f);
  f.resize(3000);
  for (size_t i = 0; i < f.size(); ++i) f.positions[i] = Vec3f(u(rng), u(rng), u(rng)), f.types[i] = DiffuseType(i % 3);
  f.positions[0] = Vec3f(0.01f, 0.0f, 0.0f);  // contains the camera
  Camera cam;
  cam.position = Vec3f::Zero(), cam.target = Vec3f(0.3f, -0.2f, -1.0f), cam.width = 96, cam.height = 54;
  for (int spp : {1, 2}) {
    VolumeSettings v = settings(VolumeIntegrator::Exact, ExactMethod::ScreenBins);
    v.samples_per_pixel = spp;
    const VolumeImage bins = render_volume(f, cam, v);
    v.exact_method = ExactMethod::EmbreeAllHits;
    const VolumeImage hits = render_volume(f, cam, v);
    double worst = 0.0;
    for (size_t i = 0; i < bins.pixel_count(); ++i) worst = std::max(worst, double(std::abs(bins.transmittance[i] - hits.transmittance[i])));
    EXPECT_LT(worst, 1e-5) << spp;
  }
}

TEST(VolumeDeterminism, JitterDependsOnSeedOnly) {
  const Scene sc = busy_scene();
  VolumeSettings v = settings(VolumeIntegrator::Exact, ExactMethod::ScreenBins);
  const VolumeImage a = render_volume(sc.frame, sc.cam, v);
  EXPECT_TRUE(same_bytes(a, render_volume(sc.frame, sc.cam, v)));
  v.seed = 100;
  EXPECT_FALSE(same_bytes(a, render_volume(sc.frame, sc.cam, v)));
}

}  // namespace
}  // namespace spume
