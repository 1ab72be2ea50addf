// Emission (MODEL.md §1 Eq. 8, §2, §8.3, §8.7): statistics with fixed seeds and stated significance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/core/rng.h"
#include "sim/diffuse/emission.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

// Kolmogorov-Smirnov distance between samples and a CDF; the critical value at significance 0.001 is
// 1.95 / sqrt(n).
template <typename Cdf>
double ks_distance(std::vector<double> x, Cdf cdf) {
  std::sort(x.begin(), x.end());
  double d = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double f = cdf(x[i]);
    d = std::max({d, f - double(i) / x.size(), double(i + 1) / x.size() - f});
  }
  return d;
}

TEST(CylinderSampling, RadialAzimuthalAndAxialDistributionsAreUniformOverTheCylinder) {
  const Vec3f x_f(1, 2, 3), v_f(0, 3, 4);  // speed 5
  const float dt = 0.02f, radius = 0.1f;   // axis length |dt v| = 0.1
  const Vec3f axis = v_f.normalized();
  const int n = 20000;
  std::vector<double> radial, angle, along;
  Vec3f e1 = Vec3f::Zero();
  for (int i = 0; i < n; ++i) {
    const auto u = random_uniform4({11, RandomPurpose::CylinderSample, 0, uint64_t(i), 0});
    Vec3f x, v;
    sample_cylinder(x_f, v_f, v_f, dt, radius, u, x, v);
    const Vec3f d = x - x_f;
    const float l = d.dot(axis);
    const Vec3f perp = d - l * axis;
    if (i == 0) e1 = perp.normalized();
    radial.push_back(perp.norm() / radius);
    const Vec3f e2 = axis.cross(e1);
    angle.push_back(std::atan2(perp.dot(e2), perp.dot(e1)) + M_PI);
    along.push_back(l / (dt * 5.0f));
    // The velocity is the fluid's plus the radial offset (as printed in the paper).
    ASSERT_NEAR((v - v_f - perp).norm(), 0.0f, 1e-5f);
  }
  const double critical = 1.95 / std::sqrt(double(n));
  // Uniform over the disc: P(rho <= s) = s^2.
  EXPECT_LT(ks_distance(radial, [](double s) { return std::clamp(s * s, 0.0, 1.0); }), critical);
  EXPECT_LT(ks_distance(angle, [](double a) { return std::clamp(a / (2 * M_PI), 0.0, 1.0); }), critical);
  EXPECT_LT(ks_distance(along, [](double l) { return std::clamp(l, 0.0, 1.0); }), critical);
}

TEST(CylinderSampling, RestingParticleSamplesADiscWithoutNaN) {
  Vec3f x, v;
  sample_cylinder(Vec3f(1, 1, 1), Vec3f::Zero(), Vec3f::Zero(), 0.02f, 0.1f, {0.5f, 0.25f, 0.9f, 0.0f}, x, v);
  EXPECT_TRUE(finite(x) && finite(v));
  EXPECT_NEAR((x - Vec3f(1, 1, 1)).norm(), 0.1f * std::sqrt(0.5f), 1e-6);
}

TEST(StochasticRounding, ExpectedCountIsKeptForAnyStep) {
  // A particle asking for 0.7 samples per 0.02 s over 1 s must get 35 samples on average, whether
  // the second is cut into 50, 100 or 400 steps. Mean over 4000 particles; the count per particle has
  // variance below steps * 1/4, so 5 standard errors of the mean are under 5 * sqrt(400/4/4000) = 0.8.
  const float rate = 35.0f;  // per second
  for (int steps : {50, 100, 400}) {
    const float expected_per_step = rate / float(steps);
    double total = 0;
    for (uint32_t particle = 0; particle < 4000; ++particle)
      for (int s = 0; s < steps; ++s)
        total += round_emission(expected_per_step, {3, RandomPurpose::EmissionRounding, uint32_t(s), particle, 0});
    EXPECT_NEAR(total / 4000.0, 35.0, 0.8) << steps << " steps";
  }
}

TEST(StochasticRounding, WholeNumbersAreExactAndZeroGivesNothing) {
  EXPECT_EQ(round_emission(3.0f, {1, RandomPurpose::EmissionRounding, 0, 0, 0}), 3u);
  EXPECT_EQ(round_emission(0.0f, {1, RandomPurpose::EmissionRounding, 0, 0, 0}), 0u);
  EXPECT_EQ(round_emission(-1.0f, {1, RandomPurpose::EmissionRounding, 0, 0, 0}), 0u);
}

TEST(Lifetime, GrowsLinearlyWithThePotential) {
  DiffuseParams p;
  p.k_ta = 100, p.k_wc = 300, p.lifetime_min = 2, p.lifetime_max = 6;
  EXPECT_FLOAT_EQ(emission_lifetime(p, 0, 0, 1), 2.0f);
  EXPECT_FLOAT_EQ(emission_lifetime(p, 1, 1, 1), 6.0f);
  // P = 0.5 (100 * 1 + 300 * 0) / 400 = 0.125 -> 2 + 4 * 0.125 = 2.5.
  EXPECT_FLOAT_EQ(emission_lifetime(p, 1, 0, 0.5f), 2.5f);
}

// 2000 emitters along x in [0, 2), each asking for exactly 1 sample (I_k = 1, I_ta = 1, k_ta dt = 1).
struct EmitterLine {
  FluidStepState state;
  FormationPotentials potentials;
  DiffuseParams params;
  EmitterLine() {
    std::vector<Vec3f> x, v;
    for (int i = 0; i < 2000; ++i) x.emplace_back(0.001f * i, 0, 0), v.emplace_back(0, 1, 0);
    state = testing::state_of(x, v);
    potentials.trapped_air.assign(x.size(), 1.0f);
    potentials.wave_crest.assign(x.size(), 0.0f);
    potentials.kinetic.assign(x.size(), 1.0f);
    params.k_ta = 50.0f, params.k_wc = 0.0f, params.lifetime_min = 1, params.lifetime_max = 2;
  }
};

TEST(EmissionBudget, KeepsExactlyTheRoomAndThinsUniformlyInSpace) {
  EmitterLine line;
  line.params.max_particles = 600;
  DiffuseFrame out;
  out.resize(100);  // 100 already alive: room for 500 of the 2000 candidates
  const auto r = emit_diffuse(line.state, line.potentials, line.params, 0, 0.02f, 0.01f, out);
  EXPECT_TRUE(r.budget_bound);
  EXPECT_EQ(r.requested, 2000u);
  EXPECT_EQ(r.emitted, 500u);
  EXPECT_EQ(out.size(), 600u);
  // Unbiased in space: each half of the line keeps 250 on average; a hypergeometric count has sd
  // below sqrt(500 * 0.5 * 0.5) = 11.2, so 4 sd is 45.
  int left = 0;
  for (size_t k = 100; k < out.size(); ++k) left += out.positions[k].x() < 1.0f;
  EXPECT_NEAR(left, 250, 45);
}

TEST(EmissionBudget, NewParticlesCarryStableIdsAndLifetimes) {
  EmitterLine line;
  DiffuseFrame out;
  const auto r = emit_diffuse(line.state, line.potentials, line.params, 7, 0.02f, 0.01f, out);
  EXPECT_FALSE(r.budget_bound);
  ASSERT_EQ(out.size(), 2000u);
  for (size_t k = 0; k < out.size(); ++k) {
    ASSERT_EQ(diffuse_id_parent(out.ids[k]), uint32_t(k));
    ASSERT_EQ(diffuse_id_step(out.ids[k]), 7u);
    ASSERT_EQ(diffuse_id_sample(out.ids[k]), 0u);
    ASSERT_FLOAT_EQ(out.lifetimes[k], 2.0f);  // full potential
  }
}

}  // namespace
}  // namespace spume
