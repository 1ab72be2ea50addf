// fluid.solver.start_clearance: starting lattice points within a distance of a box or sphere are left
// out. The distance test against hand-worked distances (edges and rotated boxes included, where
// testing along the axes alone would be wrong), and the solver's starting fluid against a lattice
// counted here by brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/fluid/solver.h"
#include "sim/geometry/solids.h"

namespace spume {
namespace {

Solid sphere(const Vec3f& centre, float radius) {
  Solid s;
  s.kind = Solid::Kind::Sphere;
  s.center = centre;
  s.radius = radius;
  return s;
}

Solid box(const Vec3f& lo, const Vec3f& hi, Solid::Kind kind = Solid::Kind::Box) {
  Solid s;
  s.kind = kind;
  s.min = lo;
  s.max = hi;
  return s;
}

TEST(SolidSetObstacleWithin, MeasuresTheDistanceToSpheresAndBoxes) {
  const SolidSet ball({sphere(Vec3f(0, 0, 0), 1.0f)});
  EXPECT_TRUE(ball.obstacle_within(Vec3f(0.5f, 0, 0), 0.01f));  // inside
  EXPECT_TRUE(ball.obstacle_within(Vec3f(1.3f, 0, 0), 0.31f));  // 0.3 from the surface
  EXPECT_FALSE(ball.obstacle_within(Vec3f(1.3f, 0, 0), 0.29f));
  const float diagonal = 1.2f / std::numbers::sqrt2_v<float>;  // |p| = 1.2: 0.2 from the surface
  EXPECT_TRUE(ball.obstacle_within(Vec3f(diagonal, diagonal, 0), 0.21f));
  EXPECT_FALSE(ball.obstacle_within(Vec3f(diagonal, diagonal, 0), 0.19f));

  const SolidSet cube({box(Vec3f(0, 0, 0), Vec3f(1, 1, 1))});
  EXPECT_TRUE(cube.obstacle_within(Vec3f(0.5f, 0.5f, 1.1f), 0.11f));  // 0.1 above the top face
  EXPECT_FALSE(cube.obstacle_within(Vec3f(0.5f, 0.5f, 1.1f), 0.09f));
  // Beside an edge: 0.2 out along x and along y is sqrt(0.08) = 0.283 from the box, not 0.2.
  EXPECT_TRUE(cube.obstacle_within(Vec3f(1.2f, 1.2f, 0.5f), 0.29f));
  EXPECT_FALSE(cube.obstacle_within(Vec3f(1.2f, 1.2f, 0.5f), 0.28f));
  // Beyond a corner: 0.1 out along each axis, sqrt(0.03) = 0.173.
  EXPECT_TRUE(cube.obstacle_within(Vec3f(-0.1f, -0.1f, -0.1f), 0.18f));
  EXPECT_FALSE(cube.obstacle_within(Vec3f(-0.1f, -0.1f, -0.1f), 0.17f));

  // A 2 x 1 x 1 bar turned 90 degrees about z lies along y: its end faces are at y = +-1.
  Solid bar = box(Vec3f(-1, -0.5f, -0.5f), Vec3f(1, 0.5f, 0.5f));
  bar.orientation = Quatf(Eigen::AngleAxisf(0.5f * std::numbers::pi_v<float>, Vec3f::UnitZ()));
  const SolidSet turned({bar});
  EXPECT_TRUE(turned.obstacle_within(Vec3f(0, 1.2f, 0), 0.21f));
  EXPECT_FALSE(turned.obstacle_within(Vec3f(0, 1.2f, 0), 0.19f));
  EXPECT_TRUE(turned.obstacle_within(Vec3f(0.7f, 0, 0), 0.21f));  // 0.2 beside its side face x = 0.5
  EXPECT_FALSE(turned.obstacle_within(Vec3f(0.7f, 0, 0), 0.19f));

  // Tanks are not obstacles: their walls are the fluid lattice's own business.
  const SolidSet tank({box(Vec3f(0, 0, 0), Vec3f(1, 1, 1), Solid::Kind::Tank)});
  EXPECT_FALSE(tank.obstacle_within(Vec3f(0.01f, 0.5f, 0.5f), 0.5f));
}

// A sphere cutting a block: the solver starts with exactly the lattice points at least R + clearance
// from the centre (R alone without a clearance), counted here from the lattice's definition.
TEST(FluidStartClearance, LeavesOutTheLatticePointsNearASolidAndCountsThem) {
  const float r = 0.025f, d = 2.0f * r;
  const Vec3f centre(0.5f, 0.0f, 0.5f);
  const float radius = 0.3f;
  const FluidBlock block{Vec3f(0, 0, 0), Vec3f(1.0f, 0.5f, 1.0f)};  // 20 x 10 x 20 points, at (i + 1/2) d
  const SolidSet solids({box(Vec3f(0, 0, 0), Vec3f(1.0f, 1.0f, 1.0f), Solid::Kind::Tank), sphere(centre, radius)});
  for (const float clearance : {0.0f, 0.5f, 1.0f}) {
    const double limit = double(radius) + double(clearance) * double(r);
    size_t kept = 0;
    double closest_to_limit = INFINITY;
    for (int k = 0; k < 20; ++k)
      for (int j = 0; j < 10; ++j)
        for (int i = 0; i < 20; ++i) {
          const double dx = (i + 0.5) * d - centre.x(), dy = (j + 0.5) * d - centre.y(), dz = (k + 0.5) * d - centre.z();
          const double dist = std::sqrt(dx * dx + dy * dy + dz * dz);
          closest_to_limit = std::min(closest_to_limit, std::abs(dist - limit));
          kept += dist >= limit;
        }
    // No lattice point sits on the limit, where float and double rounding could disagree.
    ASSERT_GT(closest_to_limit, 1e-4) << clearance;
    FluidSolverParams p;
    p.particle_radius = r;
    p.start_clearance = clearance;
    FluidSolver solver(p, {block}, solids);
    EXPECT_EQ(solver.size(), kept) << "clearance " << clearance << " r";
    EXPECT_EQ(solver.size() + solver.stats().removed_at_start, 4000u) << clearance;
  }
}

}  // namespace
}  // namespace spume
