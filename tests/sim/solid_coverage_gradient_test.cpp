// The gradient a solid adds to the surface test (geometry/solid_coverage.h) at a tank's edges,
// corners and open rim, worked by hand.
//
// The gradient of the solid part S of the ball is G = ∫_S ∇_x W(x - y) dy. Over the whole ball it is
// zero, and it is additive in S. With y = x + r u, ∇_x W(x - y) = -W'(r) u, so for a region bounded
// by planes through x, G = -(∫_0^h W'(r) r^2 dr) ∫_dirs(S) u dΩ = (W0 / π) ∫_dirs(S) u dΩ, pointing
// into the solid, where W0 = 2π ∫_0^h W(s) s ds is a flat wall's gradient at its face (by parts:
// ∫ W' r^2 dr = -2 ∫ W r dr). For the cubic spline W = 8 / (π h^3) f(r / h),
// ∫_0^1 f(q) q dq = 0.06875 + 0.01875 = 0.0875, so W0 = 16 x 0.0875 / h = 1.4 / h. Then, on:
//  - a wall's face (half-space, ∫ u over a hemisphere = π n):  |G| = W0 = 1.4 / h
//  - an edge (two walls: the free quadrant's ∫ u = (π/2, π/2, 0)): G = -(W0 / 2)(1, 1, 0)
//  - a corner (three walls; free octant, ∫ u = (π/4)(1, 1, 1)):   G = -(W0 / 4)(1, 1, 1)
//  - an open rim (the wall ends: the solid is one quadrant):      G = -(W0 / 2)(1, 1, 0)
// Off those lines, additivity links the shapes: an edge plus the quadrant it lacks is two walls, and a
// closed lid is the open rim plus a flat lid.
#include <gtest/gtest.h>

#include <numbers>

#include "sim/diffuse/kernels.h"
#include "sim/geometry/solid_coverage.h"

namespace spume {
namespace {

constexpr float kH = 0.1f;
constexpr double kW0 = 1.4 / kH;
// The quadrature over 256 directions (away from single faces): within 2% of a wall's gradient.
constexpr double kTolerance = 0.02 * kW0;

SolidSet tank(bool open_top) {
  Solid s;
  s.kind = Solid::Kind::Tank;
  s.min = Vec3f::Zero(), s.max = Vec3f::Ones(), s.open_top = open_top;
  return SolidSet({s});
}

// 2π ∫_d^h W(s) s ds by the midpoint rule: a flat wall's gradient at distance d from it.
double wall_gradient(double d) {
  const CubicSpline w(kH);
  const int n = 20000;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double s = d + (i + 0.5) * (kH - d) / n;
    sum += double(w.value(float(s))) * s * (kH - d) / n;
  }
  return 2 * std::numbers::pi * sum;
}

// A ball's cap beyond a plane at distance d, as a share of the ball.
double cap(double d) {
  const double x = d / kH;
  return (1 - x) * (1 - x) * (2 + x) / 4;
}

void expect_gradient(const Vec3f& g, const Vec3d& expected, const char* what) {
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(g[a], expected[a], kTolerance) << what << " axis " << a;
}

TEST(SolidCoverageGradient, TheWallsGradientIsOnePointFourOverH) {
  EXPECT_NEAR(wall_gradient(0.0), kW0, 1e-4 * kW0);  // the quadrature of the hand-worked constant
  const SolidCoverage c = solid_coverage(tank(true), {0.5f, 0.0f, 0.5f}, kH, true);
  EXPECT_NEAR(c.gradient.y(), -kW0, 1e-3 * kW0);
}

TEST(SolidCoverageGradient, EdgesAndCornersOfATankHalveAndQuarterIt) {
  const SolidSet closed = tank(false);
  // Floor edges (x = 0 and x = 1) and a vertical edge, each pointing into both of its walls.
  expect_gradient(solid_coverage(closed, {0, 0, 0.5f}, kH, true).gradient, -kW0 / 2 * Vec3d(1, 1, 0), "x0 floor edge");
  expect_gradient(solid_coverage(closed, {1, 0, 0.5f}, kH, true).gradient, kW0 / 2 * Vec3d(1, -1, 0), "x1 floor edge");
  expect_gradient(solid_coverage(closed, {1, 0.5f, 1}, kH, true).gradient, kW0 / 2 * Vec3d(1, 0, 1), "vertical edge");
  // Under a closed lid too.
  expect_gradient(solid_coverage(closed, {0.5f, 1, 0}, kH, true).gradient, kW0 / 2 * Vec3d(0, 1, -1), "lid edge");
  // Corners: a quarter of a wall's gradient on each axis, towards each wall.
  for (int corner = 0; corner < 8; ++corner) {
    Vec3f p;
    Vec3d expected;
    for (int a = 0; a < 3; ++a) {
      const bool high = (corner >> a) & 1;
      p[a] = high ? 1.0f : 0.0f;
      expected[a] = (high ? 1.0 : -1.0) * kW0 / 4;
    }
    const SolidCoverage c = solid_coverage(closed, p, kH, true);
    expect_gradient(c.gradient, expected, ("corner " + std::to_string(corner)).c_str());
    EXPECT_NEAR(c.fraction, 7.0 / 8.0, 0.01) << corner;
  }
}

TEST(SolidCoverageGradient, AnOpenRimIsAQuarterAndALidAddsAFlatWall) {
  // On the rim of the x = 0 wall the wall ends: into the wall and down.
  const SolidSet open = tank(true), closed = tank(false);
  expect_gradient(solid_coverage(open, {0, 1, 0.5f}, kH, true).gradient, -kW0 / 2 * Vec3d(1, 1, 0), "rim");
  expect_gradient(solid_coverage(open, {1, 1, 0.5f}, kH, true).gradient, kW0 / 2 * Vec3d(1, -1, 0), "far rim");
  // Near the rim, inside, above or beside it: the closed tank is the open one plus the lid's half-
  // space y > 1, whose share and gradient are the flat-wall ones at distance |1 - y|.
  for (const Vec3f& p : {Vec3f(0.03f, 0.96f, 0.5f), Vec3f(0.05f, 1.04f, 0.5f), Vec3f(-0.02f, 1.03f, 0.4f),
                         Vec3f(0.96f, 0.98f, 0.3f)}) {
    const SolidCoverage o = solid_coverage(open, p, kH, true), c = solid_coverage(closed, p, kH, true);
    const double d = 1.0 - double(p.y());
    const double lid = wall_gradient(std::abs(d));
    const double lid_share = d >= 0 ? cap(d) : 1.0 - cap(-d);
    EXPECT_NEAR(c.fraction - o.fraction, lid_share, 0.01) << p.transpose();
    expect_gradient(c.gradient - o.gradient, Vec3d(0, lid, 0), "lid");
  }
}

TEST(SolidCoverageGradient, OffTheEdgeAnEdgePlusTheQuadrantItLacksIsTwoWalls) {
  // Near the floor edge x = 0, y = 0 at (a, b): the edge's solid {x < 0} or {y < 0} plus the
  // quadrant {x < 0 and y < 0} is the two walls' half-spaces. That quadrant is the open tank's rim
  // wall seen from (a, 1 + b). So G_edge(a, b) + G_rim(a, 1 + b) = (-W(a), -W(b), 0), each W(d) the
  // flat wall's gradient at distance d, and the shares add up to cap(a) + cap(b).
  const SolidSet closed = tank(false), open = tank(true);
  for (const auto& [a, b] : {std::pair{0.02f, 0.05f}, std::pair{0.07f, 0.01f}, std::pair{0.04f, 0.04f}}) {
    const SolidCoverage edge = solid_coverage(closed, {a, b, 0.5f}, kH, true);
    const SolidCoverage rim = solid_coverage(open, {a, 1.0f + b, 0.5f}, kH, true);
    expect_gradient(edge.gradient + rim.gradient, Vec3d(-wall_gradient(a), -wall_gradient(b), 0), "edge + rim");
    EXPECT_NEAR(edge.fraction + rim.fraction, cap(a) + cap(b), 0.01) << a << ' ' << b;
    // The edge pulls harder towards the nearer wall.
    if (a != b) {
      EXPECT_EQ(edge.gradient.x() < edge.gradient.y(), a < b) << a << ' ' << b;
    }
  }
}

}  // namespace
}  // namespace spume
