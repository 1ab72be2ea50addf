// Rotated boxes and posed dynamic solids in SolidSet (inside, push_out, solid_coverage), hand-worked
// in the box frame, and the fluid solver's boundary sampling of a rotated box.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/core/error.h"
#include "sim/fluid/solver.h"
#include "sim/geometry/solid_coverage.h"
#include "sim/geometry/solids.h"

namespace spume {
namespace {

Solid cube(const Vec3f& centre, float half, float angle_z) {
  Solid b;
  b.kind = Solid::Kind::Box;
  b.min = centre - Vec3f::Constant(half);
  b.max = centre + Vec3f::Constant(half);
  b.orientation = Quatf(Eigen::AngleAxisf(angle_z, Vec3f::UnitZ()));
  return b;
}

TEST(RotatedSolids, InsideAndPushOutUseTheBoxFrame) {
  const float s = std::sqrt(0.5f);
  const Vec3f c(1, 2, 3);
  const SolidSet set({cube(c, 0.5f, std::numbers::pi_v<float> / 4)});
  // Along world x the turned cube reaches its edge at 0.5 sqrt(2) = 0.707 m.
  EXPECT_TRUE(set.inside(c + Vec3f(0.6f, 0, 0)));
  EXPECT_TRUE(set.inside(c + Vec3f(0.7f, 0, 0)));
  EXPECT_FALSE(set.inside(c + Vec3f(0.72f, 0, 0)));
  EXPECT_FALSE(set.inside(c + Vec3f(0.45f, 0.45f, 0)));  // beyond the face at 0.5 along (1, 1) / sqrt 2
  // c + (0.68, 0.02, 0) is at (0.7 s, -0.66 s, 0) = (0.495, -0.467, 0) in the box frame: nearest to the
  // local +x face, whose world normal is (s, s, 0), 0.5 - 0.7 s = 5 mm inside.
  const float depth = 0.5f - 0.7f * s;
  Vec3f p = c + Vec3f(0.68f, 0.02f, 0), v(-1, 0, 0);
  ASSERT_TRUE(set.push_out(p, v, 0.0f));
  EXPECT_NEAR(p.x(), c.x() + 0.68f + depth * s, 1e-5f);
  EXPECT_NEAR(p.y(), c.y() + 0.02f + depth * s, 1e-5f);
  EXPECT_FALSE(set.inside(p + Vec3f(1e-4f, 1e-4f, 0)));
  // The normal component of v (-s) is removed: v - (v . n) n = (-1, 0, 0) + s (s, s, 0).
  EXPECT_NEAR(v.x(), -0.5f, 1e-5f);
  EXPECT_NEAR(v.y(), 0.5f, 1e-5f);
}

TEST(RotatedSolids, SolidCoverageMeasuresDistanceInTheBoxFrame) {
  const Vec3f c(0, 0, 0);
  const float angle = 0.4f;
  const SolidSet set({cube(c, 0.5f, angle)});
  const Vec3f normal(std::cos(angle), std::sin(angle), 0);  // the local +x face, turned
  const float h = 0.3f, d = 0.1f;
  // A sphere of radius h whose centre is d outside a plane holds the cap pi (h - d)^2 (2h + d) / 3.
  const float cap = std::numbers::pi_v<float> * (h - d) * (h - d) * (2 * h + d) / 3;
  const float ball = 4.0f / 3.0f * std::numbers::pi_v<float> * h * h * h;
  EXPECT_NEAR(solid_coverage(set, c + (0.5f + d) * normal, h, false).fraction * ball, cap, 1e-5f);
  // Unrotated, the same point is 0.053 m from the x face and sees more solid.
  const SolidSet upright({cube(c, 0.5f, 0.0f)});
  EXPECT_GT(solid_coverage(upright, c + (0.5f + d) * normal, h, false).fraction * ball, cap + 1e-3f);
}

TEST(RotatedSolids, PushOutGivesTheRotatingWallsSpeed) {
  Solid box = cube(Vec3f::Zero(), 0.5f, 0.0f);
  box.angular_velocity = Vec3f(0, 0, -1);  // the +x face at y = 0.4 moves at w x r = (0.4, -0.5, 0)
  const SolidSet set({box});
  Vec3f p(0.45f, 0.4f, 0), v = Vec3f::Zero();
  ASSERT_TRUE(set.push_out(p, v, 0.0f));
  EXPECT_NEAR(p.x(), 0.5f, 1e-6f);
  EXPECT_NEAR(v.x(), 0.4f, 1e-6f);  // the face's normal speed
  EXPECT_EQ(v.y(), 0.0f);
}

TEST(RotatedSolids, PosedMovesDynamicSolidsAndValidateRejectsWhatSolversCannotDo) {
  Solid body = cube(Vec3f(0, 1, 0), 0.1f, 0.0f);
  body.dynamics.enabled = true;
  body.dynamics.density = 500;
  Solid wall = cube(Vec3f(3, 0, 0), 0.5f, 0.0f);
  const SolidSet set({wall, body});
  BodyPose pose;
  pose.solid = 1;
  pose.position = Vec3f(2, 0.5f, -1);
  pose.orientation = Quatf(Eigen::AngleAxisf(1.0f, Vec3f::UnitX()));
  pose.velocity = Vec3f(0, -1, 0);
  const SolidSet now = set.posed({pose});
  EXPECT_TRUE(now.solids()[1].centre().isApprox(pose.position));
  EXPECT_TRUE((now.solids()[1].max - now.solids()[1].min).isApprox(Vec3f::Constant(0.2f)));
  EXPECT_TRUE(now.solids()[1].orientation.isApprox(pose.orientation));
  EXPECT_EQ(now.solids()[1].velocity, pose.velocity);
  EXPECT_TRUE(now.inside(pose.position + Vec3f(0.09f, 0, 0)));
  EXPECT_FALSE(now.inside(Vec3f(0, 1, 0)));
  EXPECT_EQ(now.solids()[0].min, wall.min);
  pose.solid = 0;  // not dynamic
  EXPECT_THROW(set.posed({pose}), Error);

  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.max = Vec3f(1, 1, 1);
  tank.orientation = Quatf(Eigen::AngleAxisf(0.1f, Vec3f::UnitY()));
  EXPECT_THROW(SolidSet({tank}).validate(), Error);
  Solid no_mass = body;
  no_mass.dynamics.density = 0;
  EXPECT_THROW(SolidSet({no_mass}).validate(), Error);
  EXPECT_NO_THROW(set.validate());
}

TEST(RotatedSolids, FluidSolverSamplesAndClearsARotatedBox) {
  FluidSolverParams p;
  p.particle_radius = 0.01f;
  const Vec3f c(0.2f, 0.2f, 0.2f);
  const float angle = 0.5f;
  const SolidSet solids({cube(c, 0.08f, angle)});
  FluidSolver solver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(0.4f, 0.4f, 0.4f)}}, solids);
  const Eigen::Matrix3f to_box = Eigen::AngleAxisf(-angle, Vec3f::UnitZ()).toRotationMatrix();
  // Boundary particles: inside the turned box, within h = 0.04 m of a face.
  const std::vector<Vec3f> b = solver.boundary_positions();
  ASSERT_FALSE(b.empty());
  for (const Vec3f& x : b) {
    const Vec3f local = (to_box * (x - c)).cwiseAbs();
    EXPECT_LT(local.maxCoeff(), 0.08f) << x.transpose();
    EXPECT_GT(local.maxCoeff(), 0.08f - 0.04f) << x.transpose();
  }
  // No fluid particle starts inside it.
  for (const Vec3f& x : solver.frame(0).positions) EXPECT_GE((to_box * (x - c)).cwiseAbs().maxCoeff(), 0.08f);
}

}  // namespace
}  // namespace spume
