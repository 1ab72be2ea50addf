// SolidClearance, the grid that lets the diffuse model skip its per-particle solid tests: where it says
// clear, the exact tests must have nothing to do (push_out and stop_at_tank_walls leave the particle as it
// is, the solid share of its ball is exactly zero), which is checked directly and against distances
// computed here in double; and it must say clear wherever the nearest solid or wall is a few cells
// beyond the reach, or it would save nothing. Points are drawn uniformly, just either side of the reach
// of every wall and solid, and on the grid's own cell sides, near the origin and 1 km away.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "sim/geometry/solid_clearance.h"
#include "sim/geometry/solid_coverage.h"
#include "sim/geometry/solids.h"
#include "tests/support/solid_shapes.h"

namespace spume {
namespace {

using testing::box_solid;
using testing::sphere_solid;
using testing::tank_solid;

// Distance from p to a box or sphere (0 inside), in double, the rotation normalised.
double distance_to(const Solid& s, const Vec3d& p) {
  if (s.kind == Solid::Kind::Sphere) return std::max(0.0, (p - s.center.cast<double>()).norm() - double(s.radius));
  const Vec3d c = 0.5 * (s.min.cast<double>() + s.max.cast<double>()), half = 0.5 * (s.max - s.min).cast<double>();
  const Vec3d local = s.orientation.cast<double>().normalized().conjugate() * (p - c);
  return (local.cwiseAbs() - half).cwiseMax(0.0).norm();
}

// How far p lies inside the tank's walls along every walled axis (negative: beyond a wall).
double inside_margin(const Solid& tank, const Vec3d& p) {
  double margin = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    margin = std::min(margin, p[a] - double(tank.min[a]));
    if (!(tank.open_top && a == tank.up_axis)) margin = std::min(margin, double(tank.max[a]) - p[a]);
  }
  return margin;
}

// Distance in the max norm from p to the box around a box or sphere's extent (a rotated box: around its corners).
double box_gap(const Solid& s, const Vec3d& p) {
  Vec3d lo, hi;
  if (s.kind == Solid::Kind::Sphere) {
    lo = s.center.cast<double>() - Vec3d::Constant(s.radius), hi = s.center.cast<double>() + Vec3d::Constant(s.radius);
  } else {
    const Vec3d c = 0.5 * (s.min.cast<double>() + s.max.cast<double>()), half = 0.5 * (s.max - s.min).cast<double>();
    const Eigen::Quaterniond q = s.orientation.cast<double>().normalized();
    lo = Vec3d::Constant(INFINITY), hi = Vec3d::Constant(-INFINITY);
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3d local(corner & 1 ? half.x() : -half.x(), corner & 2 ? half.y() : -half.y(), corner & 4 ? half.z() : -half.z());
      const Vec3d w = c + q * local;
      lo = lo.cwiseMin(w), hi = hi.cwiseMax(w);
    }
  }
  return (lo - p).cwiseMax(p - hi).maxCoeff();
}

struct Verdicts {
  int clear = 0, should_be_clear = 0;
};

// Checks every point: clear ones leave the exact tests nothing to do; points well away from everything
// are clear.
Verdicts check_points(const SolidSet& solids, const SolidClearance& clearance, float h, const std::vector<Vec3f>& points,
                      std::mt19937& rng) {
  Verdicts verdicts;
  const double cell = clearance.cell_size();
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (const Vec3f& p : points) {
    const Vec3d pd = p.cast<double>();
    double tank_margin = INFINITY, solid_distance = INFINITY, solid_gap = INFINITY;
    for (const Solid& s : solids.solids()) {
      if (s.kind == Solid::Kind::Tank) {
        tank_margin = std::min(tank_margin, inside_margin(s, pd));
      } else {
        solid_distance = std::min(solid_distance, distance_to(s, pd));
        solid_gap = std::min(solid_gap, box_gap(s, pd));
      }
    }
    const bool clear = clearance.clear(p);
    if (clear) {
      ++verdicts.clear;
      SCOPED_TRACE(::testing::Message() << "clear point " << p.transpose());
      EXPECT_GE(solid_distance, 0.999 * h);
      EXPECT_GE(tank_margin, 0.999 * h);
      Vec3f moved = p, v(0.3f, -2.0f, 0.1f);
      EXPECT_FALSE(solids.push_out(moved, v, 1e-6f));
      EXPECT_EQ(moved, p);
      // A step ending here crossed no wall, wherever it began (outside the tank too).
      const Vec3f from = p + Vec3f(unit(rng), unit(rng), unit(rng)) * 3.0f;
      Vec3f end = p;
      EXPECT_FALSE(solids.stop_at_tank_walls(from, end, v, 1e-6f));
      EXPECT_EQ(end, p);
      const SolidCoverage cover = solid_coverage(solids, p, h, true);
      EXPECT_EQ(cover.fraction, 0.0f);
      EXPECT_EQ(cover.gradient, Vec3f::Zero());
      const CoverageBounds bounds = solid_coverage_bounds(solids, p, h);
      EXPECT_EQ(bounds.lo, 0.0f);
      EXPECT_EQ(bounds.hi, 0.0f);
    }
    // Three cells (their diagonals) beyond the reach and the broad phase's padding: nothing is near.
    const double room = h * 1.01 + 3.0 * std::sqrt(3.0) * cell + 1e-3;
    const bool inside_tanks = std::isinf(tank_margin) || tank_margin >= room;
    // An open top is closed at the rim for the grid: points above it take the exact tests.
    bool below_rims = true;
    for (const Solid& s : solids.solids())
      if (s.kind == Solid::Kind::Tank && s.open_top) below_rims &= pd[s.up_axis] <= double(s.max[s.up_axis]) - room;
    if (inside_tanks && below_rims && solid_gap >= room) {
      ++verdicts.should_be_clear;
      EXPECT_TRUE(clear) << "point " << p.transpose() << " is " << solid_gap << " m from every solid's box and "
                         << tank_margin << " m inside the walls";
    }
  }
  return verdicts;
}

// Points: uniform over the box widened by 10%, at the reach (plus or minus 1%) of every wall and solid
// surface, and on the sides of the grid's cells.
std::vector<Vec3f> sample_points(const SolidSet& solids, const SolidClearance& clearance, const Vec3f& lo,
                                 const Vec3f& hi, float h, std::mt19937& rng) {
  std::vector<Vec3f> points;
  const Vec3f pad = 0.1f * (hi - lo);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), near(0.99f, 1.01f);
  auto uniform = [&] {
    const Vec3f t(u(rng), u(rng), u(rng));
    return Vec3f(lo - pad + t.cwiseProduct(hi - lo + 2.0f * pad));
  };
  for (int k = 0; k < 40000; ++k) points.push_back(uniform());
  for (const Solid& s : solids.solids())
    for (int k = 0; k < 8000; ++k) {
      Vec3f p = uniform();
      const float gap = h * near(rng);
      if (s.kind == Solid::Kind::Tank) {
        const int a = int(rng() % 3);
        p[a] = rng() % 2 ? s.min[a] + gap : s.max[a] - gap;
      } else if (s.kind == Solid::Kind::Sphere) {
        Vec3f d(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f);
        p = s.center + (s.radius + gap) * d.normalized();
      } else {
        const Vec3f c = 0.5f * (s.min + s.max), half = 0.5f * (s.max - s.min);
        Vec3f local((2 * u(rng) - 1) * half.x(), (2 * u(rng) - 1) * half.y(), (2 * u(rng) - 1) * half.z());
        const int a = int(rng() % 3);
        local[a] = (rng() % 2 ? 1.0f : -1.0f) * (half[a] + gap);
        p = c + s.orientation * local;
      }
      points.push_back(p);
    }
  // On the cells' sides (as clear() rounds them) and a few ulps either side.
  const float cell = clearance.cell_size();
  for (int k = 0; k < 20000; ++k) {
    Vec3f p = uniform();
    const int a = int(rng() % 3);
    const float side = lo[a] + std::round((p[a] - lo[a]) / cell) * cell;
    p[a] = side;
    for (int ulps = int(rng() % 5); ulps > 0; --ulps) p[a] = std::nextafter(p[a], rng() % 2 ? INFINITY : -INFINITY);
    points.push_back(p);
  }
  return points;
}

TEST(SolidClearance, ClearPointsLeaveTheExactTestsNothingAndOpenWaterIsClear) {
  const float h = 0.03f;
  Quatf tilted(Eigen::AngleAxisf(0.5f, Vec3f(1, 2, 3).normalized()));
  for (const Vec3f& origin : {Vec3f(0, 0, 0), Vec3f(1000, -500, 2000)})
    for (bool open_top : {true, false}) {
      SCOPED_TRACE(::testing::Message() << "origin " << origin.transpose() << (open_top ? ", open top" : ", closed"));
      // The paper-scale lighthouse's solids, and a tilted box.
      const SolidSet solids({tank_solid(origin + Vec3f(0, 0, 0), origin + Vec3f(4.0f, 1.4f, 2.0f), open_top),
                             box_solid(origin + Vec3f(0.0f, 0.0f, 0.0f), origin + Vec3f(0.12f, 1.4f, 2.0f)),
                             sphere_solid(origin + Vec3f(2.7f, -0.05f, 1.0f), 0.45f),
                             box_solid(origin + Vec3f(2.58f, 0.3f, 0.88f), origin + Vec3f(2.82f, 1.05f, 1.12f)),
                             box_solid(origin + Vec3f(1.2f, 0.4f, 0.5f), origin + Vec3f(1.5f, 0.6f, 0.7f), tilted)});
      const SolidClearance clearance(solids, h);
      ASSERT_TRUE(clearance.built());
      EXPECT_GE(clearance.cell_size(), 0.999f * h);  // cells of the reach (as rounded)
      std::mt19937 rng(5);
      const auto points = sample_points(solids, clearance, origin, origin + Vec3f(4.0f, 1.4f, 2.0f), h, rng);
      const Verdicts v = check_points(solids, clearance, h, points, rng);
      // Much of the tank is open water: the checks above must have had something to check.
      EXPECT_GT(v.should_be_clear, 10000);
      EXPECT_GE(v.clear, v.should_be_clear);
    }
}

TEST(SolidClearance, WithoutATankEverythingBeyondTheSolidsIsClear) {
  const float h = 0.05f;
  Quatf tilted(Eigen::AngleAxisf(1.1f, Vec3f(0, 1, 1).normalized()));
  const SolidSet solids({box_solid(Vec3f(-1, 0, 0), Vec3f(-0.5f, 0.3f, 0.4f), tilted), sphere_solid(Vec3f(2, 1, 0), 0.3f)});
  const SolidClearance clearance(solids, h);
  std::mt19937 rng(9);
  const auto points = sample_points(solids, clearance, Vec3f(-1.5f, -0.5f, -0.5f), Vec3f(2.5f, 1.5f, 0.5f), h, rng);
  const Verdicts v = check_points(solids, clearance, h, points, rng);
  EXPECT_GT(v.should_be_clear, 10000);
  // Far outside the grid, and not a number.
  EXPECT_TRUE(clearance.clear(Vec3f(100, -50, 30)));
  EXPECT_FALSE(clearance.clear(Vec3f(std::nanf(""), 0, 0)));
  EXPECT_FALSE(clearance.clear(Vec3f(INFINITY, 0, 0)));
}

TEST(SolidClearance, NoSolidsClearEveryFinitePointAndAnUnbuiltGridNone) {
  const SolidClearance none(SolidSet{}, 0.03f);
  EXPECT_TRUE(none.clear(Vec3f(0, 0, 0)));
  EXPECT_TRUE(none.clear(Vec3f(-1e30f, 5, 1e20f)));
  EXPECT_FALSE(none.clear(Vec3f(std::nanf(""), 0, 0)));
  const SolidClearance unbuilt;
  EXPECT_FALSE(unbuilt.built());
  EXPECT_FALSE(unbuilt.clear(Vec3f(0, 0, 0)));
  // A tank's outside is never clear; nor is a tank too thin to hold a ball of the reach.
  const SolidSet thin({tank_solid(Vec3f(0, 0, 0), Vec3f(1, 0.04f, 1), false)});
  const SolidClearance thin_clearance(thin, 0.03f);
  EXPECT_EQ(thin_clearance.clear_cells(), 0u);
  EXPECT_FALSE(thin_clearance.clear(Vec3f(5, 0.02f, 0.5f)));
}

}  // namespace
}  // namespace spume
