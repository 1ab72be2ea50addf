// Kinematic solids: motions in closed form, snapshots at a time, and push_out against moving walls.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/core/error.h"
#include "sim/geometry/solids.h"

namespace spume {
namespace {

TEST(SolidMotion, SineOffsetAndVelocityFollowTheFormula) {
  Motion m;
  m.kind = Motion::Kind::Sine;
  m.axis = Vec3f(0, 0, 1);
  m.amplitude = 0.1f;
  m.frequency = 0.5f;
  m.phase = 0.3f;
  m.start = 1.0;
  const double w = 2 * std::numbers::pi * 0.5;
  for (double t : {1.0, 1.25, 2.0, 3.7}) {
    EXPECT_NEAR(m.offset(t).z(), 0.1 * std::sin(w * (t - 1.0) + 0.3), 1e-6) << t;
    EXPECT_NEAR(m.velocity(t).z(), 0.1 * w * std::cos(w * (t - 1.0) + 0.3), 1e-5) << t;
    EXPECT_EQ(m.offset(t).x(), 0.0f);
  }
  // Before the start it rests where it will start.
  EXPECT_NEAR(m.offset(0.2).z(), 0.1 * std::sin(0.3), 1e-6);
  EXPECT_EQ(m.velocity(0.2), Vec3f::Zero());
}

TEST(SolidMotion, KeyframesArePiecewiseLinearAndHeldOutside) {
  Motion m;
  m.kind = Motion::Kind::Keyframes;
  m.times = {1.0, 2.0, 4.0};
  m.offsets = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 2, 0)};
  EXPECT_TRUE(m.offset(0.0).isApprox(Vec3f(0, 0, 0)));
  EXPECT_TRUE(m.offset(1.5).isApprox(Vec3f(0.5f, 0, 0)));
  EXPECT_TRUE(m.offset(3.0).isApprox(Vec3f(1, 1, 0)));
  EXPECT_TRUE(m.offset(9.0).isApprox(Vec3f(1, 2, 0)));
  EXPECT_TRUE(m.velocity(1.5).isApprox(Vec3f(1, 0, 0)));
  EXPECT_TRUE(m.velocity(3.0).isApprox(Vec3f(0, 1, 0)));
  EXPECT_EQ(m.velocity(0.5), Vec3f::Zero());
  EXPECT_EQ(m.velocity(4.5), Vec3f::Zero());
  m.times = {1.0, 1.0, 4.0};
  EXPECT_THROW(m.validate("test"), Error);
}

TEST(SolidSet, AtTimeMovesSolidsAndPushOutWorksRelativeToTheWall) {
  Solid piston;
  piston.kind = Solid::Kind::Box;
  piston.min = Vec3f(0, 0, 0);
  piston.max = Vec3f(0.1f, 1, 1);
  piston.motion.kind = Motion::Kind::Keyframes;
  piston.motion.times = {0.0, 1.0};
  piston.motion.offsets = {Vec3f::Zero(), Vec3f(0.5f, 0, 0)};
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(-1, -1, -1);
  tank.max = Vec3f(2, 2, 2);
  const SolidSet set({piston, tank});
  EXPECT_TRUE(set.any_moving());
  const SolidSet now = set.at_time(0.5);
  EXPECT_FALSE(now.any_moving());
  EXPECT_TRUE(now.solids()[0].min.isApprox(Vec3f(0.25f, 0, 0)));
  EXPECT_TRUE(now.solids()[0].velocity.isApprox(Vec3f(0.5f, 0, 0)));
  EXPECT_EQ(now.solids()[1].min, tank.min);  // static solids are unchanged

  // A particle just inside the moving piston's front face, at rest: pushed out in front of the face,
  // and given the wall's normal speed (it must not stay behind a wall that moves into it).
  Vec3f p(0.34f, 0.5f, 0.5f), v = Vec3f::Zero();
  EXPECT_TRUE(now.inside(p));
  EXPECT_TRUE(now.push_out(p, v, 0.01f));
  EXPECT_NEAR(p.x(), 0.36f, 1e-6f);
  EXPECT_NEAR(v.x(), 0.5f, 1e-6f);
  EXPECT_FALSE(now.inside(p));
  // Moving away from the wall faster than it: untouched velocity.
  Vec3f q(0.34f, 0.5f, 0.5f), u(2.0f, 0, 0);
  now.push_out(q, u, 0.0f);
  EXPECT_EQ(u, Vec3f(2.0f, 0, 0));
}

TEST(SolidSet, StaticPushOutKeepsItsBehaviour) {
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(0, 0, 0);
  tank.max = Vec3f(1, 1, 1);
  const SolidSet set({tank});
  Vec3f p(0.5f, -0.1f, 0.5f), v(0.3f, -2.0f, 0.0f);
  EXPECT_TRUE(set.push_out(p, v, 0.05f));
  EXPECT_NEAR(p.y(), 0.05f, 1e-6f);
  EXPECT_EQ(v, Vec3f(0.3f, 0.0f, 0.0f));
  Vec3f above(0.5f, 1.5f, 0.5f), w = Vec3f::Zero();
  EXPECT_FALSE(set.push_out(above, w, 0.05f));  // open top
  EXPECT_EQ(set.at_time(3.0).solids()[0].min, tank.min);
}

}  // namespace
}  // namespace spume
