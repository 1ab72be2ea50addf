// Formation (MODEL.md §1): each equation on configurations worked by hand.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/diffuse/kernels.h"
#include "sim/diffuse/potentials.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

TEST(ClampAndScale, IsZeroBelowOneAboveAndLinearBetween) {
  EXPECT_FLOAT_EQ(clamp_and_scale(-3.0f, 2.0f, 8.0f), 0.0f);
  EXPECT_FLOAT_EQ(clamp_and_scale(2.0f, 2.0f, 8.0f), 0.0f);
  EXPECT_FLOAT_EQ(clamp_and_scale(5.0f, 2.0f, 8.0f), 0.5f);   // (5 - 2) / 6
  EXPECT_FLOAT_EQ(clamp_and_scale(8.0f, 2.0f, 8.0f), 1.0f);
  EXPECT_FLOAT_EQ(clamp_and_scale(1e9f, 2.0f, 8.0f), 1.0f);
}

TEST(PaperWeight, FallsLinearlyToZeroAtTheInfluenceRadius) {
  EXPECT_FLOAT_EQ(paper_weight(0.0f, 2.0f), 1.0f);
  EXPECT_FLOAT_EQ(paper_weight(0.5f, 2.0f), 0.75f);
  EXPECT_FLOAT_EQ(paper_weight(2.0f, 2.0f), 0.0f);
  EXPECT_FLOAT_EQ(paper_weight(2.5f, 2.0f), 0.0f);
}

TEST(CubicSpline, IntegratesToOneOverItsSupport) {
  const CubicSpline k(0.3f);
  // Radial integral 4 pi r^2 W(r) dr by the midpoint rule.
  double sum = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double r = (i + 0.5) * 0.3 / n;
    sum += 4 * M_PI * r * r * k.value(float(r)) * (0.3 / n);
  }
  EXPECT_NEAR(sum, 1.0, 1e-5);
}

DiffuseParams formation_params() {
  DiffuseParams p;
  p.trapped_air = {0.25f, 2.0f};
  p.wave_crest = {0.5f, 2.5f};
  p.kinetic = {0.1f, 0.3f};
  p.surface_threshold = 0.3f;
  p.k_ta = p.k_wc = 1.0f;
  return p;
}

// Two particles half the influence radius apart (h = 1, W = 0.5). With V = 0.2 the colour gradient
// is V |W'(0.5)| h = 0.2 * 12/pi = 0.76 >= 0.3: both are surface particles.
FormationPotentials pair_potentials(const Vec3f& vi, const Vec3f& vj, float volume = 0.2f) {
  const auto state = testing::state_of({Vec3f(0, 0, 0), Vec3f(0.5f, 0, 0)}, {vi, vj});
  NeighbourGrid grid;
  grid.build(state.positions, 1.0f);
  FormationPotentials out;
  compute_potentials(grid, state, formation_params(), volume, nullptr, out);
  return out;
}

TEST(TrappedAir, ApproachingPairCountsTwiceRecedingPairNever) {
  // Both move at 0.5 m/s (E = 0.125 J, above tau_k's min, so the sums are evaluated).
  // Approaching: v_ij = (1,0,0), x^_ij = (-1,0,0): |v_ij| (1 - (-1)) W = 1 * 2 * 0.5 = 1 for both.
  // I_ta = (1 - 0.25) / (2 - 0.25) = 3/7.
  auto approaching = pair_potentials(Vec3f(0.5f, 0, 0), Vec3f(-0.5f, 0, 0));
  EXPECT_NEAR(approaching.trapped_air[0], 3.0f / 7.0f, 1e-6);
  EXPECT_NEAR(approaching.trapped_air[1], 3.0f / 7.0f, 1e-6);
  // Receding: v^_ij . x^_ij = 1, so the factor is 0.
  auto receding = pair_potentials(Vec3f(-0.5f, 0, 0), Vec3f(0.5f, 0, 0));
  EXPECT_EQ(receding.trapped_air[0], 0.0f);
  EXPECT_EQ(receding.trapped_air[1], 0.0f);
  // Sliding past: factor 1, v_diff = 1 * 1 * 0.5 = 0.5, I_ta = 0.25 / 1.75 = 1/7.
  auto sliding = pair_potentials(Vec3f(0, 0.5f, 0), Vec3f(0, -0.5f, 0));
  EXPECT_NEAR(sliding.trapped_air[0], 1.0f / 7.0f, 1e-6);
}

TEST(TrappedAir, ParticlesTooSlowToEmitGetNoPotential) {
  // Eq. 8 multiplies by I_k, so a resting particle's sums are skipped and reported as zero.
  auto p = pair_potentials(Vec3f(1, 0, 0), Vec3f(0, 0, 0));
  EXPECT_NEAR(p.trapped_air[0], 3.0f / 7.0f, 1e-6);
  EXPECT_EQ(p.kinetic[1], 0.0f);
  EXPECT_EQ(p.trapped_air[1], 0.0f);
}

TEST(TrappedAir, RigidTranslationTrapsNoAir) {
  auto points = testing::lattice(Vec3f::Zero(), Vec3f(1, 1, 1), 0.1f);
  testing::jitter(points, 0.02f, 1);
  const std::vector<Vec3f> v(points.size(), Vec3f(3, -1, 2));
  const auto state = testing::state_of(points, v);
  NeighbourGrid grid;
  grid.build(state.positions, 0.2f);
  FormationPotentials out;
  compute_potentials(grid, state, formation_params(), 0.001f, nullptr, out);
  for (float i : out.trapped_air) ASSERT_EQ(i, 0.0f);
}

TEST(KineticEnergy, ClampsHalfMassSpeedSquared) {
  // m = 1 (test state), |v| = 0.5 -> E = 0.125; I_k = (0.125 - 0.1) / 0.2 = 0.125.
  auto p = pair_potentials(Vec3f(0.5f, 0, 0), Vec3f(0, 0, 0));
  EXPECT_NEAR(p.kinetic[0], 0.125f, 1e-6);
  EXPECT_EQ(p.kinetic[1], 0.0f);
}

TEST(WaveCrest, SeparatingPairIsConvexWithHandWorkedCurvature) {
  // Each normal points away from the other: n_0 = (-1,0,0), n_1 = (1,0,0). For particle 0,
  // x^_10 . n_0 = -1 < 0 (convex), kappa = (1 - n_0.n_1) W(0.5, 2h) = 2 * 0.75 = 1.5 (the crest sum
  // reaches 2 h, MODEL.md §8.10); I_wc = (1.5 - 0.5) / 2 = 0.5 when it moves along its normal.
  auto p = pair_potentials(Vec3f(-1, 0, 0), Vec3f(1, 0, 0));
  EXPECT_NEAR((p.normals[0] - Vec3f(-1, 0, 0)).norm(), 0.0f, 1e-6);
  EXPECT_NEAR((p.normals[1] - Vec3f(1, 0, 0)).norm(), 0.0f, 1e-6);
  EXPECT_NEAR(p.wave_crest[0], 0.5f, 1e-6);
  EXPECT_NEAR(p.wave_crest[1], 0.5f, 1e-6);
}

TEST(WaveCrest, OnlyParticlesMovingAlongTheirNormalWithinPoint6) {
  // cos(angle) between v and n_0 = (-1,0,0) just above and just below 0.6.
  const auto at = [](float c) { return Vec3f(-c, std::sqrt(1 - c * c), 0); };
  EXPECT_NEAR(pair_potentials(at(0.61f), Vec3f(1, 0, 0)).wave_crest[0], 0.5f, 1e-6);
  EXPECT_EQ(pair_potentials(at(0.59f), Vec3f(1, 0, 0)).wave_crest[0], 0.0f);
}

TEST(WaveCrest, InteriorParticlesHaveNoNormal) {
  // Gradient magnitude below the threshold: a tiny particle volume makes |grad c| h tiny.
  auto p = pair_potentials(Vec3f(-1, 0, 0), Vec3f(1, 0, 0), 1e-6f);
  EXPECT_EQ(p.normals[0], Vec3f::Zero());
  EXPECT_EQ(p.wave_crest[0], 0.0f);
}

// Mean crest curvature over the surface particles of a sphere of radius R: a droplet (convex) or a
// spherical void inside a block (concave). Lattice spacing 0.05, h = 0.1, R = 0.3. Every particle
// moves along its own normal so Eq. 7 passes wherever there is a normal: only Eq. 6 tells the two
// apart. A smooth sphere's neighbours at distance d differ in normal by d/R, so for the droplet
// kappa ~ sum (d/R)^2/2 (1 - d/2h) over the surface neighbours within the crest sum's 2 h; the void
// counts none of them (they lie in front of the particle), only lattice noise.
float mean_crest_curvature(bool droplet) {
  // Concentric shells of Fibonacci-sphere points (smooth surfaces; a lattice sphere's staircase is
  // full of small convex corners) at spacing 0.05, four shells deep.
  const float spacing = 0.05f, h = 0.1f, radius = 0.3f;
  const Vec3f centre(0.6f, 0.6f, 0.6f);
  std::vector<Vec3f> points;
  const float golden = float(M_PI) * (3.0f - std::sqrt(5.0f));
  for (int shell = 0; shell < 4; ++shell) {
    const float rho = droplet ? radius - shell * spacing : radius + shell * spacing;
    const int n = int(std::lround(4.0f * float(M_PI) * rho * rho / (spacing * spacing)));
    for (int i = 0; i < n; ++i) {
      const float y = 1.0f - 2.0f * (i + 0.5f) / n, ring = std::sqrt(1.0f - y * y), phi = golden * i + shell;
      points.push_back(centre + rho * Vec3f(ring * std::cos(phi), y, ring * std::sin(phi)));
    }
  }
  // The void's block goes on beyond the shells (on a lattice), so that its outer faces lie farther than
  // the crest sum's reach (2 h) from the void: four shells alone would be a hollow ball whose thin wall
  // is a sheet, convex on its far side.
  if (!droplet)
    for (const Vec3f& p : testing::lattice(centre - Vec3f::Constant(0.8f), centre + Vec3f::Constant(0.8f), spacing))
      if ((p - centre).norm() > radius + 3.5f * spacing) points.push_back(p);
  auto state = testing::state_of(points, std::vector<Vec3f>(points.size(), Vec3f::Zero()));
  NeighbourGrid grid;
  grid.build(state.positions, h);
  DiffuseParams params = formation_params();
  params.wave_crest = {0.0f, 1000.0f};  // I_wc = kappa / 1000: read the raw curvature back
  const float volume = spacing * spacing * spacing;
  std::vector<Vec3f> normals;
  compute_normals(grid, volume, params, nullptr, normals);
  state.velocities = normals;
  FormationPotentials out;
  compute_potentials(grid, state, params, volume, nullptr, out);
  double sum = 0;
  int count = 0;
  for (size_t i = 0; i < points.size(); ++i)
    if (std::abs((points[i] - centre).norm() - radius) < 0.5f * spacing && out.normals[i].squaredNorm() > 0) {
      sum += out.wave_crest[i] * 1000.0f;
      ++count;
    }
  EXPECT_GT(count, 100);
  return float(sum / count);
}

TEST(WaveCrest, ConvexDropletFormsCrestsConcaveVoidDoesNot) {
  const float convex = mean_crest_curvature(true), concave = mean_crest_curvature(false);
  EXPECT_GT(convex, 0.05f);
  EXPECT_LT(concave, 0.25f * convex) << "convex " << convex;
}

TEST(Formation, FlatPoolRisingUniformlyFormsNothing) {
  // A jittered pool whose surface moves outward along its normal: Eq. 7 passes, yet a flat surface
  // has no curvature and uniform motion traps no air, so with the paper's thresholds nothing forms.
  auto points = testing::lattice(Vec3f::Zero(), Vec3f(1.2f, 0.6f, 1.2f), 0.1f);
  testing::jitter(points, 0.01f, 7);
  const auto state = testing::state_of(points, std::vector<Vec3f>(points.size(), Vec3f(0, 1.0f, 0)));
  NeighbourGrid grid;
  grid.build(state.positions, 0.2f);
  DiffuseParams params = formation_params();
  params.wave_crest = {2.0f, 8.0f};
  FormationPotentials out;
  compute_potentials(grid, state, params, 0.001f, nullptr, out);
  int surface = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    surface += out.normals[i].y() > 0.9f;
    ASSERT_EQ(out.trapped_air[i], 0.0f);
    // Farther from the pool's vertical sides than the crest radius (2h) and the jitter, every
    // neighbour Eq. 6 sums over lies on the flat top.
    const Vec3f& p = points[i];
    const float lo = 2 * 0.2f + 0.02f, hi = 1.2f - lo;
    if (p.x() > lo && p.x() < hi && p.z() > lo && p.z() < hi) {
      ASSERT_EQ(out.wave_crest[i], 0.0f) << i;
    }
  }
  EXPECT_GT(surface, 100);  // the top layer has upward normals
}

}  // namespace
}  // namespace spume
