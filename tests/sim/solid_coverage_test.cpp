// The share of a ball inside the union of solids, and the gradient it adds (geometry/solid_coverage.h),
// against closed forms and Monte Carlo estimates that use only SolidSet::inside.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "sim/diffuse/kernels.h"
#include "sim/geometry/solid_coverage.h"
#include "tests/support/solid_shapes.h"

namespace spume {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;

Solid tank(const Vec3f& lo, const Vec3f& hi, bool open_top = true) { return testing::tank_solid(lo, hi, open_top); }
Solid box(const Vec3f& lo, const Vec3f& hi) { return testing::box_solid(lo, hi); }
Solid sphere(const Vec3f& c, float radius) { return testing::sphere_solid(c, radius); }

// Share of the ball of radius h around p inside the solids, by 400k uniform points (fixed seed):
// standard error below 0.0008.
double monte_carlo_fraction(const SolidSet& solids, const Vec3f& p, float h) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  int inside = 0, total = 0;
  while (total < 400000) {
    const Vec3f d(u(rng), u(rng), u(rng));
    if (d.squaredNorm() > 1.0f) continue;
    ++total;
    inside += solids.inside(p + h * d);
  }
  return double(inside) / total;
}

// Cap beyond a plane at distance d from the centre of a ball of radius h, over the ball's volume.
double cap_fraction(double d, double h) { return kPi * (h - d) * (h - d) * (2 * h + d) / 3 / (4.0 / 3 * kPi * h * h * h); }

// 2 pi ∫_d^h W(s) s ds by the midpoint rule: the gradient a flat solid beyond distance d adds.
double plane_gradient(double d, float h) {
  const CubicSpline w(h);
  const int n = 20000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double s = d + (i + 0.5) * (h - d) / n;
    sum += w.value(float(s)) * s * (h - d) / n;
  }
  return 2 * std::numbers::pi * sum;
}

TEST(SolidCoverage, NothingWithinReachCoversNothing) {
  const SolidSet solids({tank({0, 0, 0}, {1, 1, 1})});
  const SolidCoverage c = solid_coverage(solids, {0.5f, 0.5f, 0.5f}, 0.1f, true);
  EXPECT_EQ(c.fraction, 0.0f);
  EXPECT_EQ(c.gradient, Vec3f::Zero());
}

TEST(SolidCoverage, FlatFloorIsTheSphericalCapWithTheDiscGradient) {
  const float h = 0.1f;
  const SolidSet solids({tank({0, 0, 0}, {1, 1, 1})});
  for (float d : {0.0f, 0.03f, 0.07f}) {
    const SolidCoverage c = solid_coverage(solids, {0.5f, d, 0.5f}, h, true);
    EXPECT_NEAR(c.fraction, cap_fraction(d, h), 1e-6) << d;
    EXPECT_NEAR(c.fraction, monte_carlo_fraction(solids, {0.5f, d, 0.5f}, h), 0.004) << d;
    // The gradient points into the floor (-y) with the disc integral's size.
    EXPECT_NEAR(c.gradient.y(), -plane_gradient(d, h), 1e-3 * plane_gradient(0, h)) << d;
    EXPECT_NEAR(c.gradient.x(), 0.0f, 1e-6f);
    EXPECT_NEAR(c.gradient.z(), 0.0f, 1e-6f);
  }
}

TEST(SolidCoverage, EdgeAndCornerOfATankCountTheUnionNotTheSumOfFaces) {
  const float h = 0.1f;
  const SolidSet solids({tank({0, 0, 0}, {1, 1, 1})});
  // On an edge two half-spaces cover 3/4 of the ball (a sum over faces would say 1); in a corner
  // three cover 7/8 (a sum would say 3/2).
  EXPECT_NEAR(solid_coverage(solids, {0.5f, 0, 0}, h, false).fraction, 0.75, 0.01);
  EXPECT_NEAR(solid_coverage(solids, {0, 0, 0}, h, false).fraction, 0.875, 0.01);
  // Off the edge, against Monte Carlo.
  const Vec3f p(0.5f, 0.04f, 0.06f);
  EXPECT_NEAR(solid_coverage(solids, p, h, false).fraction, monte_carlo_fraction(solids, p, h), 0.01);
}

TEST(SolidCoverage, OpenRimAndClosedLidDiffer) {
  const float h = 0.1f;
  // At the top of a side wall of an open tank the wall ends: a quarter of the ball is wall.
  const Vec3f on_rim(0.0f, 1.0f, 0.5f);
  const SolidSet open({tank({0, 0, 0}, {1, 1, 1}, true)});
  EXPECT_NEAR(solid_coverage(open, on_rim, h, false).fraction, 0.25, 0.01);
  EXPECT_NEAR(solid_coverage(open, on_rim + Vec3f(0.03f, 0.02f, 0), h, false).fraction,
              monte_carlo_fraction(open, on_rim + Vec3f(0.03f, 0.02f, 0), h), 0.01);
  // With a lid the same point is on an edge.
  const SolidSet closed({tank({0, 0, 0}, {1, 1, 1}, false)});
  EXPECT_NEAR(solid_coverage(closed, on_rim, h, false).fraction, 0.75, 0.01);
}

TEST(SolidCoverage, ABoxAgainstATankWallIsOneWall) {
  // A piston (box) flush against the tank's x = 0 wall: together they are the half-space x < 0.1,
  // so a point d beyond the piston sees one cap, not the piston's plus the wall's.
  const float h = 0.2f, d = 0.05f;
  const SolidSet solids({tank({0, 0, 0}, {2, 1, 1}), box({0, 0, 0}, {0.1f, 1, 1})});
  const Vec3f p(0.1f + d, 0.5f, 0.5f);
  const SolidCoverage c = solid_coverage(solids, p, h, true);
  EXPECT_NEAR(c.fraction, cap_fraction(d, h), 0.01);
  EXPECT_NEAR(c.gradient.x(), -plane_gradient(d, h), 0.02 * plane_gradient(0, h));
  EXPECT_NEAR(c.gradient.y(), 0.0f, 0.02 * plane_gradient(0, h));
}

TEST(SolidCoverage, SpheresAndBoxesAgainstMonteCarlo) {
  const float h = 0.1f;
  const SolidSet solids({sphere({0, 0, 0}, 0.2f), box({0.15f, -0.05f, -0.05f}, {0.3f, 0.05f, 0.05f})});
  for (const Vec3f& p : {Vec3f(0.25f, 0, 0), Vec3f(0.22f, 0.08f, 0.02f), Vec3f(0, 0.25f, 0), Vec3f(0.35f, 0.06f, 0)})
    EXPECT_NEAR(solid_coverage(solids, p, h, false).fraction, monte_carlo_fraction(solids, p, h), 0.012)
        << p.transpose();
}

TEST(SolidCoverage, DeepInsideASolidIsFullyCovered) {
  const SolidSet solids({box({0, 0, 0}, {1, 1, 1})});
  EXPECT_NEAR(solid_coverage(solids, {0.5f, 0.5f, 0.5f}, 0.1f, false).fraction, 1.0f, 1e-6f);
  const SolidSet under_floor({tank({0, 0, 0}, {1, 1, 1})});
  EXPECT_NEAR(solid_coverage(under_floor, {0.5f, -0.5f, 0.5f}, 0.1f, false).fraction, 1.0f, 1e-6f);
}

TEST(SolidCoverage, BoundsHoldTheIntegralAndAreExactWhereItIsNotNeeded) {
  // A tank with a box on its floor against a wall, a rotated box and a sphere: 2000 points (fixed
  // seed) around them, every bound checked against the integral.
  const float h = 0.1f;
  Solid turned = box({0.5f, 0.1f, 0.4f}, {0.7f, 0.3f, 0.6f});
  turned.orientation = Quatf(Eigen::AngleAxisf(0.5f, Vec3f(1, 1, 0).normalized()));
  const SolidSet solids({tank({0, 0, 0}, {1, 1, 1}), box({0, 0, 0}, {0.2f, 0.2f, 1}), turned,
                         sphere({0.8f, 0.6f, 0.2f}, 0.1f)});
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.05f, 1.05f);
  int exact = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3f p(u(rng), u(rng), u(rng));
    const CoverageBounds b = solid_coverage_bounds(solids, p, h);
    const float f = solid_coverage(solids, p, h, false).fraction;
    ASSERT_LE(b.lo, b.hi) << p.transpose();
    // The bounds hold the true share; the integral is within its quadrature error (0.5%) of it.
    EXPECT_LE(b.lo, f + 0.005f) << p.transpose();
    EXPECT_GE(b.hi, f - 0.005f) << p.transpose();
    if (b.lo == b.hi) {
      EXPECT_EQ(b.lo, f) << p.transpose();
      ++exact;
    }
  }
  EXPECT_GT(exact, 1000);  // most points: no solid or one face within reach
}

TEST(WetWallCount, ScalesByTheFreeShareAndStaysFinite) {
  EXPECT_FLOAT_EQ(wet_wall_count(0.0f, 0.5f), 0.0f);      // a dry wall adds nothing
  EXPECT_FLOAT_EQ(wet_wall_count(16.0f, 0.5f), 32.0f);    // half the ball is wall
  EXPECT_FLOAT_EQ(wet_wall_count(10.0f, 0.0f), 10.0f);
  EXPECT_FLOAT_EQ(wet_wall_count(3.0f, 1.0f), 30.0f);     // free share floored at 1/10
}

}  // namespace
}  // namespace spume
