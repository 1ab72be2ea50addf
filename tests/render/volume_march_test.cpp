// The march integrator (Eq. 9 as written) converges to the exact one at first order in dx.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/volume/volume_pass.h"

namespace spume {
namespace {

struct Field {
  Camera cam;
  DiffuseFrame frame;
  float r = 0.05f;
};

// 400 spheres in a 1 m box seen whole, with enough overlap for unions to matter.
Field random_field() {
  Field f;
  f.cam.position = Vec3f(0.4f, 0.7f, 3.0f);
  f.cam.target = Vec3f::Zero();
  f.cam.fov_y_degrees = 30.0f;
  f.cam.width = 96, f.cam.height = 64;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  f.frame.resize(400);
  for (size_t i = 0; i < 400; ++i) {
    f.frame.positions[i] = Vec3f(u(rng), u(rng), u(rng));
    f.frame.types[i] = i % 3 == 0 ? DiffuseType::Spray : DiffuseType::Foam;
  }
  return f;
}

VolumeImage render(const Field& f, VolumeIntegrator integrator, float dx) {
  VolumeSettings s;
  s.look[size_t(DiffuseType::Spray)] = {f.r, Vec3f(1, 0, 0)};
  s.look[size_t(DiffuseType::Foam)] = {f.r, Vec3f(0, 0, 1)};
  s.alpha = 8.0f;
  s.integrator = integrator;
  s.march_step = dx;
  return render_volume(f.frame, f.cam, s);
}

double rmse(const VolumeImage& a, const VolumeImage& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.pixel_count(); ++i) sum += std::pow(double(a.transmittance[i]) - b.transmittance[i], 2);
  return std::sqrt(sum / double(a.pixel_count()));
}

TEST(VolumeMarch, ConvergesToExactAtFirstOrder) {
  const Field f = random_field();
  const VolumeImage exact = render(f, VolumeIntegrator::Exact, 0.0f);
  // dx = 2r .. r/8, halving; least-squares slope of log(error) against log(dx).
  std::vector<double> lx, ly;
  for (float dx = 2.0f * f.r; dx >= f.r / 8.0f * 0.999f; dx *= 0.5f) {
    const double e = rmse(render(f, VolumeIntegrator::March, dx), exact);
    ASSERT_GT(e, 0.0);
    lx.push_back(std::log(double(dx)));
    ly.push_back(std::log(e));
  }
  ASSERT_EQ(lx.size(), 5u);
  const double n = double(lx.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < lx.size(); ++i) sx += lx[i], sy += ly[i], sxx += lx[i] * lx[i], sxy += lx[i] * ly[i];
  const double order = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  EXPECT_NEAR(order, 1.0, 0.2) << "errors: " << std::exp(ly.front()) << " .. " << std::exp(ly.back());
  EXPECT_LT(std::exp(ly.back()), 0.01);  // dx = r/8 is already close
}

TEST(VolumeMarch, ColourMatchesExactWhenStepIsSmall) {
  const Field f = random_field();
  const VolumeImage exact = render(f, VolumeIntegrator::Exact, 0.0f);
  const VolumeImage march = render(f, VolumeIntegrator::March, f.r / 64.0f);
  double worst = 0.0;
  for (size_t i = 0; i < exact.pixel_count(); ++i)
    if (exact.transmittance[i] < 0.9f) worst = std::max(worst, double((exact.color[i] - march.color[i]).cwiseAbs().maxCoeff()));
  EXPECT_LT(worst, 0.05);
}

}  // namespace
}  // namespace spume
