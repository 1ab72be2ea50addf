// Parts of the model worked by hand: the sampling cylinder follows the motion (MODEL.md §2), Eq. 8
// with both potentials at once, foam dissolution (§5), and the kernel slopes the potentials use.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "sim/core/rng.h"
#include "sim/diffuse/emission.h"
#include "sim/diffuse/kernels.h"
#include "sim/diffuse/simulator.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

TEST(CylinderSampling, TheAxisFollowsTheMotionAndTheVelocityIsTheFluids) {
  // The fluid particle moves along +x over the step (motion 5 m/s) while its velocity at t points up
  // (an impact turns it): the samples lie along x, their velocities are v_f plus the radial offset.
  const Vec3f x_f(1, 2, 3), motion(5, 0, 0), v_f(0, 5, 0);
  const float dt = 0.02f, radius = 0.01f;
  for (uint32_t i = 0; i < 500; ++i) {
    const auto u = random_uniform4({5, RandomPurpose::CylinderSample, 0, i, 0});
    Vec3f x, v;
    sample_cylinder(x_f, motion, v_f, dt, radius, u, x, v);
    const Vec3f d = x - x_f;
    ASSERT_GE(d.x(), -1e-6f);
    ASSERT_LE(d.x(), dt * 5.0f + 1e-6f);                      // along the 0.1 m path
    ASSERT_LE(std::hypot(d.y(), d.z()), radius + 1e-6f);      // within r_V of it
    const Vec3f radial(0, d.y(), d.z());
    ASSERT_NEAR((v - v_f - radial).norm(), 0.0f, 1e-5f);
  }
}

TEST(Formation, EquationEightAddsBothPotentialsWeightedByTheirRates) {
  // n_d = I_k (k_ta I_ta + k_wc I_wc) dt = 0.5 (100 x 0.25 + 40 x 0.75) x 0.02 = 0.55 per particle.
  // Over 20000 particles with stochastic rounding the mean is within 5 standard errors,
  // 5 sqrt(0.55 x 0.45 / 20000) = 0.018, of 0.55.
  const size_t n = 20000;
  std::vector<Vec3f> x(n), v(n, Vec3f(0, 1, 0));
  for (size_t i = 0; i < n; ++i) x[i] = Vec3f(0.01f * float(i % 100), 0.01f * float(i / 100), 0);
  const FluidStepState state = testing::state_of(x, v);
  FormationPotentials potentials;
  potentials.kinetic.assign(n, 0.5f);
  potentials.trapped_air.assign(n, 0.25f);
  potentials.wave_crest.assign(n, 0.75f);
  DiffuseParams params;
  params.k_ta = 100.0f, params.k_wc = 40.0f, params.lifetime_min = 1, params.lifetime_max = 2;
  DiffuseFrame out;
  const EmissionResult r = emit_diffuse(state, potentials, params, 7, 0.02f, 0.005f, out);
  EXPECT_NEAR(double(r.emitted) / n, 0.55, 0.018);
  // Lifetime from P = I_k (k_ta I_ta + k_wc I_wc) / (k_ta + k_wc) = 0.5 x 55 / 140: 1 + P.
  ASSERT_GT(out.size(), 0u);
  EXPECT_NEAR(out.lifetimes[0], 1.0f + 0.5f * 55.0f / 140.0f, 1e-5f);
}

TEST(Dissolution, OnlyFoamLosesLifetimeAndDiesAtZero) {
  // A resting pool; three foam particles on its surface with 0.035, 0.025 and 1 s to live, a spray
  // particle in the air and a bubble deep down, with 0.01 s each: after two steps of 0.02 s, foam has
  // lost 0.04 s, the first two foam particles are gone, spray and bubbles keep their lifetimes.
  const float r = 0.02f;
  const auto water = testing::lattice(Vec3f(r, r, r), Vec3f(1 - r, 0.3f, 1 - r), 2 * r);
  DiffuseSetup setup;
  setup.fluid.particle_radius = r;
  setup.fluid.support_radius = 4 * r;
  setup.fluid.fps = 50.0;
  setup.params.k_ta = setup.params.k_wc = 0.0f;
  setup.params.gravity = Vec3f::Zero();  // nobody moves: types stay as they are
  setup.params.buoyancy = 0.0f;
  DiffuseSimulator sim(setup);
  DiffuseFrame d;
  d.resize(5);
  const Vec3f at[5] = {{0.5f, 0.32f, 0.5f}, {0.3f, 0.32f, 0.5f}, {0.7f, 0.32f, 0.5f}, {0.5f, 0.9f, 0.5f},
                       {0.5f, 0.12f, 0.5f}};
  const float life[5] = {0.035f, 0.025f, 1.0f, 0.01f, 0.01f};
  const DiffuseType type[5] = {DiffuseType::Foam, DiffuseType::Foam, DiffuseType::Foam, DiffuseType::Spray,
                               DiffuseType::Bubble};
  for (size_t i = 0; i < 5; ++i) {
    d.ids[i] = diffuse_id(uint32_t(i), 1, 0);
    d.positions[i] = at[i], d.velocities[i] = Vec3f::Zero(), d.lifetimes[i] = life[i], d.types[i] = type[i];
  }
  sim.set_particles(d);
  std::vector<FluidFrame> frames;
  for (int k = 0; k < 3; ++k)
    frames.push_back(testing::frame_of(k, k / 50.0, water, std::vector<Vec3f>(water.size(), Vec3f::Zero())));
  uint64_t dissolved = 0;
  DiffuseFrame last;
  for (int k = 0; k < 3; ++k)
    dissolved += sim.process_frame(frames[size_t(k)], k < 2 ? &frames[size_t(k) + 1] : nullptr,
                                   [&](const DiffuseFrame& f, const FrameStats&) { last = f; })
                     .dissolved;
  EXPECT_EQ(dissolved, 2u);
  ASSERT_EQ(last.size(), 3u);
  std::map<uint32_t, float> left;
  for (size_t i = 0; i < last.size(); ++i) left[diffuse_id_parent(last.ids[i])] = last.lifetimes[i];
  ASSERT_EQ(left.count(2), 1u);
  EXPECT_NEAR(left[2], 1.0f - 0.04f, 1e-6f);  // foam: two steps
  EXPECT_EQ(left[3], 0.01f);                  // spray keeps its lifetime
  EXPECT_EQ(left[4], 0.01f);                  // bubbles too
}

TEST(CubicSpline, TheSlopeThePotentialsUseIsTheKernelsDerivative) {
  const CubicSpline k(0.3f);
  for (float r : {0.01f, 0.05f, 0.1f, 0.149f, 0.151f, 0.2f, 0.29f}) {
    const float step = 1e-3f;
    const double numeric = (double(k.value(r + step)) - double(k.value(r - step))) / (2.0 * step);
    EXPECT_NEAR(k.derivative(r), numeric, 1e-2 * std::abs(numeric) + 1e-3) << r;
  }
  EXPECT_EQ(k.derivative(0.31f), 0.0f);
  EXPECT_EQ(cubic_spline_slope(1.2f, 1.44f), 0.0f);  // beyond the support, for the lane loops
  EXPECT_EQ(paper_weight_at(1.5f), 0.0f);
}

}  // namespace
}  // namespace spume
