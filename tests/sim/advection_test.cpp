// Classification (MODEL.md §3) and advection (§4, §8.4-8.6) against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <random>

#include "sim/diffuse/advection.h"
#include "sim/diffuse/fluid_sampling.h"
#include "sim/diffuse/poly6_sums.h"
#include "sim/grid/block_buffer.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

// n fluid particles at distance h/2 around the origin (spread over a sphere), then classify a
// diffuse particle at the origin through the real neighbour pass.
DiffuseType classify_with_neighbours(int n, const DiffuseType* previous = nullptr, float hysteresis = 0.0f) {
  std::vector<Vec3f> fluid;
  const float golden = float(M_PI) * (3.0f - std::sqrt(5.0f));
  for (int i = 0; i < n; ++i) {
    const float y = 1.0f - 2.0f * (i + 0.5f) / n, r = std::sqrt(1.0f - y * y), phi = golden * i;
    fluid.push_back(0.5f * Vec3f(r * std::cos(phi), y, r * std::sin(phi)));
  }
  fluid.push_back(Vec3f(1.5f, 0, 0));  // beyond h: must not count
  NeighbourGrid grid;
  grid.build(fluid, 1.0f);
  std::vector<Vec3f> motion(fluid.size(), Vec3f::Zero());
  const std::vector<Vec3f> diffuse = {Vec3f::Zero()};
  FluidSamples samples;
  sample_fluid(grid, motion, diffuse, samples);
  EXPECT_EQ(samples.neighbour_count[0], float(n));
  DiffuseParams p;
  p.hysteresis = hysteresis;
  return classify(samples.neighbour_count[0], p, previous);
}

TEST(FluidSampling, DenseCloudMatchesBruteForceCountsAndVelocities) {
  // Many diffuse particles per half-cell, so that groups are cut down to their reach before the
  // scan; the reference sums over every fluid particle with no grid at all.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float h = 0.25f;
  std::vector<Vec3f> fluid(3000), motion(3000), diffuse(20000);
  for (size_t j = 0; j < fluid.size(); ++j) {
    fluid[j] = Vec3f(u(rng), u(rng), u(rng));
    motion[j] = Vec3f(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
  }
  for (auto& p : diffuse) p = Vec3f(1.4f * u(rng) - 0.2f, 1.4f * u(rng) - 0.2f, 1.4f * u(rng) - 0.2f);
  NeighbourGrid grid;
  grid.build(fluid, h);
  std::vector<Vec3f> sorted_motion(fluid.size());
  for (size_t j = 0; j < fluid.size(); ++j) sorted_motion[j] = motion[grid.sorted_to_original()[j]];
  FluidSamples samples;
  sample_fluid(grid, sorted_motion, diffuse, samples);
  size_t with_fluid = 0;
  for (size_t i = 0; i < diffuse.size(); ++i) {
    double count = 0, borderline = 0, weight = 0;  // borderline: at h to within float rounding
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (size_t j = 0; j < fluid.size(); ++j) {
      const double q2 = (fluid[j] - diffuse[i]).cast<double>().squaredNorm() / (double(h) * h);
      if (std::abs(q2 - 1.0) < 1e-5) borderline += 1;
      if (q2 > 1.0) continue;
      count += 1;
      weight += std::pow(1.0 - q2, 3);
      sum += std::pow(1.0 - q2, 3) * motion[j].cast<double>();
    }
    ASSERT_LE(std::abs(samples.neighbour_count[i] - count), borderline) << i;
    ASSERT_NEAR(samples.kernel_sum[i], weight, 1e-4 * (1 + weight)) << i;
    if (weight > 1e-3) {
      ++with_fluid;
      ASSERT_NEAR((samples.fluid_velocity[i].cast<double>() - sum / weight).norm(), 0.0, 1e-4) << i;
    }
  }
  EXPECT_GT(with_fluid, 10000u);
  // cell_order is a permutation of the diffuse particles.
  std::vector<uint32_t> order = samples.cell_order;
  std::sort(order.begin(), order.end());
  for (uint32_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i);
}

TEST(FluidSampling, PointsSummedTogetherGetTheSumsEachGetsAlone) {
  // poly6_sums_for takes its points two at a time over the block; each point's sums must be the very
  // bits poly6_sums gives it alone (the brute-force test above checks those), for odd and even counts.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Vec3f> fluid(600), motion(600);
  for (size_t j = 0; j < fluid.size(); ++j) {
    fluid[j] = Vec3f(u(rng), u(rng), u(rng));
    motion[j] = Vec3f(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
  }
  const float h = 0.25f;
  NeighbourGrid grid;
  grid.build(fluid, h);
  BlockBuffer block;
  block.gather(grid, grid.key_of(Vec3f(0.5f, 0.5f, 0.5f)), {motion});
  std::vector<Vec3f> points(9);
  for (auto& p : points) p = Vec3f(0.4f + 0.2f * u(rng), 0.4f + 0.2f * u(rng), 0.4f + 0.2f * u(rng));
  for (uint32_t count = 1; count <= points.size(); ++count) {
    std::vector<uint32_t> which(count);
    for (uint32_t k = 0; k < count; ++k) which[k] = points.size() - 1 - k;  // any order, not 0, 1, ...
    std::vector<float> n(points.size(), -1.0f), kernel(points.size(), -1.0f);
    std::vector<Vec3f> v(points.size(), Vec3f::Constant(-1.0f));
    poly6_sums_for(block, which, points.data(), 1.0f / (h * h), 1.0f, n.data(), kernel.data(), v.data());
    for (uint32_t i : which) {
      float n1, kernel1;
      Vec3f v1;
      poly6_sums(block, points[i], 1.0f / (h * h), 1.0f, n1, kernel1, v1);
      ASSERT_EQ(std::bit_cast<uint32_t>(n[i]), std::bit_cast<uint32_t>(n1)) << count << " " << i;
      ASSERT_EQ(std::bit_cast<uint32_t>(kernel[i]), std::bit_cast<uint32_t>(kernel1)) << count << " " << i;
      for (int c = 0; c < 3; ++c) ASSERT_EQ(std::bit_cast<uint32_t>(v[i][c]), std::bit_cast<uint32_t>(v1[c])) << count;
      ASSERT_GT(n1, 0.0f);  // the points lie in the fluid
    }
    for (uint32_t i = 0; i < points.size() - count; ++i) ASSERT_EQ(n[i], -1.0f) << "point " << i << " not asked for";
  }
}

TEST(Classification, PaperThresholdsAt5And6And20And21Neighbours) {
  EXPECT_EQ(classify_with_neighbours(0), DiffuseType::Spray);
  EXPECT_EQ(classify_with_neighbours(5), DiffuseType::Spray);
  EXPECT_EQ(classify_with_neighbours(6), DiffuseType::Foam);
  EXPECT_EQ(classify_with_neighbours(20), DiffuseType::Foam);
  EXPECT_EQ(classify_with_neighbours(21), DiffuseType::Bubble);
}

TEST(Classification, HysteresisKeepsTheCurrentTypeNearALimit) {
  const DiffuseType spray = DiffuseType::Spray, foam = DiffuseType::Foam, bubble = DiffuseType::Bubble;
  EXPECT_EQ(classify_with_neighbours(6, &spray, 1.0f), DiffuseType::Spray);  // needs 7 to become foam
  EXPECT_EQ(classify_with_neighbours(7, &spray, 1.0f), DiffuseType::Foam);
  EXPECT_EQ(classify_with_neighbours(5, &foam, 1.0f), DiffuseType::Foam);    // needs < 5 to become spray
  EXPECT_EQ(classify_with_neighbours(21, &foam, 1.0f), DiffuseType::Foam);   // needs > 21 to become bubble
  EXPECT_EQ(classify_with_neighbours(20, &bubble, 1.0f), DiffuseType::Bubble);
  EXPECT_EQ(classify_with_neighbours(19, &bubble, 1.0f), DiffuseType::Foam);
}

TEST(Spray, ExactIntegratorFollowsTheParabolaForAnyStep) {
  const Vec3f x0(0, 1, 0), v0(2, 5, -1), g(0, -9.81f, 0);
  for (int steps : {1, 7, 50}) {
    Vec3f x = x0, v = v0;
    for (int i = 0; i < steps; ++i) advance_spray(x, v, g, 1.0f / steps, SprayIntegrator::Exact);
    const Vec3f expected = x0 + v0 + 0.5f * g;  // t = 1
    EXPECT_NEAR((x - expected).norm(), 0.0f, 2e-5f) << steps;
    EXPECT_NEAR((v - (v0 + g)).norm(), 0.0f, 2e-5f);
  }
}

TEST(Spray, EulerCromerIsOffByHalfGTimesStepTimesT) {
  // x_n = x0 + v0 t + g dt^2 n(n+1)/2 = exact + g t dt / 2.
  const Vec3f g(0, -9.81f, 0);
  Vec3f x = Vec3f::Zero(), v = Vec3f::Zero();
  const int n = 20;
  const float dt = 0.05f;
  for (int i = 0; i < n; ++i) advance_spray(x, v, g, dt, SprayIntegrator::EulerCromer);
  EXPECT_NEAR(x.y(), 0.5f * -9.81f * 1.0f + 0.5f * -9.81f * 1.0f * dt, 1e-4f);
}

TEST(Foam, FollowsAPrescribedRigidRotation) {
  // Fluid on a lattice of spacing 0.05 with the rotation field v = w x (w = 2 rad/s about y). Foam at
  // radius 0.3 moved by forward Euler steps x += dt w x x has the closed form: radius grows by
  // sqrt(1 + (w dt)^2) per step, angle advances by atan(w dt).
  const float w = 2.0f, dt = 0.01f, h = 0.1f;
  const auto fluid = testing::lattice(Vec3f(-0.6f, -0.2f, -0.6f), Vec3f(0.6f, 0.2f, 0.6f), 0.05f);
  std::vector<Vec3f> field;
  for (const Vec3f& p : fluid) field.push_back(Vec3f(0, w, 0).cross(p));
  NeighbourGrid grid;
  grid.build(fluid, h);
  std::vector<Vec3f> sorted_field(fluid.size());
  for (size_t j = 0; j < fluid.size(); ++j) sorted_field[j] = field[grid.sorted_to_original()[j]];
  Vec3f x(0.3f, 0.0f, 0.0f), v = Vec3f::Zero();
  const int steps = 50;
  for (int i = 0; i < steps; ++i) {
    FluidSamples s;
    const std::vector<Vec3f> at = {x};
    sample_fluid(grid, sorted_field, at, s);
    advance_foam(x, v, s.fluid_velocity[0], dt, FoamVelocity::Fluid);
    EXPECT_NEAR((v - Vec3f(0, w, 0).cross(at[0])).norm(), 0.0f, 0.02f);  // v becomes the fluid's
  }
  const float radius = 0.3f * std::pow(1.0f + w * w * dt * dt, steps / 2.0f);
  const float angle = steps * std::atan(w * dt);
  // Rotation about +y by angle maps (r, 0, 0) to (r cos a, 0, -r sin a).
  EXPECT_NEAR(x.x(), radius * std::cos(angle), 2e-3f);
  EXPECT_NEAR(x.z(), -radius * std::sin(angle), 2e-3f);
  EXPECT_NEAR(x.y(), 0.0f, 1e-4f);
}

DiffuseParams bubble_params(BubbleDrag mode, float k_d) {
  DiffuseParams p;
  p.bubble_drag = mode;
  p.drag = k_d;
  p.buoyancy = 2.0f;
  p.drag_reference_step = 0.02f;
  return p;
}

TEST(Bubble, PaperModeReachesItsTerminalRiseSpeed) {
  // Fixed point of v = v + dt k_b |g| + k_d (u - v): v - u = dt k_b |g| / k_d = 0.02 * 2 * 9.81 / 0.5.
  const auto p = bubble_params(BubbleDrag::Paper, 0.5f);
  const Vec3f u(0.3f, 0, 0);
  Vec3f x = Vec3f::Zero(), v = Vec3f::Zero();
  for (int i = 0; i < 200; ++i) advance_bubble(x, v, u, p, 0.02f);
  EXPECT_NEAR(v.y(), 0.02f * 2.0f * 9.81f / 0.5f, 1e-4f);
  EXPECT_NEAR(v.x(), 0.3f, 1e-5f);
}

TEST(Bubble, ExponentialModeMatchesPaperTerminalSpeedAtTheReferenceStepForAnyStep) {
  // Terminal v - u = tau k_b |g| with tau = 0.02 / k_d, for any dt.
  for (float dt : {0.001f, 0.02f, 0.1f}) {
    const auto p = bubble_params(BubbleDrag::Exponential, 0.5f);
    Vec3f x = Vec3f::Zero(), v = Vec3f::Zero();
    for (int i = 0; i < int(4.0f / dt); ++i) advance_bubble(x, v, Vec3f::Zero(), p, dt);
    EXPECT_NEAR(v.y(), 0.04f * 2.0f * 9.81f, 1e-4f) << dt;
  }
}

TEST(Bubble, ExponentialModeIsExactForAnyStep) {
  // Closed form with u = 0: v(t) = w + (v0 - w) e^{-t/tau}, x(t) = w t + (v0 - w) tau (1 - e^{-t/tau}).
  const auto p = bubble_params(BubbleDrag::Exponential, 0.25f);
  const double tau = 0.08, w = tau * 2 * 9.81, v0 = -1.0, t = 0.5;
  const double v_exact = w + (v0 - w) * std::exp(-t / tau);
  const double x_exact = w * t + (v0 - w) * tau * (1 - std::exp(-t / tau));
  for (int steps : {1, 10, 500}) {
    Vec3f x = Vec3f::Zero(), v(0, float(v0), 0);
    for (int i = 0; i < steps; ++i) advance_bubble(x, v, Vec3f::Zero(), p, float(t / steps));
    EXPECT_NEAR(v.y(), v_exact, 2e-5) << steps;
    EXPECT_NEAR(x.y(), x_exact, 2e-5) << steps;
  }
}

TEST(Bubble, ExponentialModeIsStableForExtremeDrag) {
  const auto p = bubble_params(BubbleDrag::Exponential, 1e6f);
  Vec3f x = Vec3f::Zero(), v(50, -20, 3);
  const Vec3f u(1, 0, 0);
  for (int i = 0; i < 100; ++i) advance_bubble(x, v, u, p, 0.02f);
  // tau = 2e-8 s: the bubble moves with the fluid plus a negligible rise tau k_b |g|.
  EXPECT_NEAR((v - u).norm(), 2e-8f * 2 * 9.81f, 1e-6f);
  EXPECT_TRUE(finite(x));
  EXPECT_NEAR(x.x(), 2.0f, 1e-4f);
}

TEST(Bubble, PaperModeOscillatesAboveOneAndDivergesAboveTwo) {
  // Why paper mode is limited to k_d <= 1: the velocity gap is multiplied by (1 - k_d) each step.
  for (float k_d : {1.5f, 2.5f}) {
    auto p = bubble_params(BubbleDrag::Paper, k_d);
    p.buoyancy = 0.0f;
    Vec3f x = Vec3f::Zero(), v(1, 0, 0);
    for (int i = 0; i < 40; ++i) advance_bubble(x, v, Vec3f::Zero(), p, 0.02f);
    EXPECT_NEAR(std::abs(v.x()), std::pow(std::abs(1 - k_d), 40.0f), 1e-3f * std::pow(std::abs(1 - k_d), 40.0f));
  }
}

}  // namespace
}  // namespace spume
