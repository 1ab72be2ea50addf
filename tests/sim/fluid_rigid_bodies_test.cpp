// Dynamic solids without fluid (fluid/rigid_bodies.h, Bullet): free fall, applied force and torque
// against Newton's laws in closed form, resting contact on a tank floor, and the skin that keeps a
// falling body a film's thickness from the solids while a body placed on them stays where it is.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/core/error.h"
#include "sim/fluid/rigid_bodies.h"

namespace spume::fluid {
namespace {

Solid box_at(const Vec3f& centre, const Vec3f& size, float density) {
  Solid b;
  b.kind = Solid::Kind::Box;
  b.min = centre - 0.5f * size;
  b.max = centre + 0.5f * size;
  b.dynamics.enabled = true;
  b.dynamics.density = density;
  return b;
}

void run(RigidBodies& bodies, double duration, double dt, const std::vector<Vec3d>& force,
         const std::vector<Vec3d>& torque) {
  const int steps = int(std::lround(duration / dt));
  for (int k = 0; k < steps; ++k) bodies.step(k * dt, dt, force, torque);
}

TEST(RigidBodies, FreeFallFollowsGravity) {
  const Vec3f g(0, -9.81f, 0);
  RigidBodies bodies(SolidSet({box_at(Vec3f(0, 5, 0), Vec3f(0.2f, 0.1f, 0.3f), 700)}), g, 0.005f);
  ASSERT_EQ(bodies.size(), 1u);
  EXPECT_NEAR(bodies.mass(0), 700.0 * 0.2 * 0.1 * 0.3, 1e-4);
  const double t = 0.2;
  run(bodies, t, 0.004, {Vec3d::Zero()}, {Vec3d::Zero()});
  const BodyPose& pose = bodies.poses()[0];
  // y = y0 - g t^2 / 2; Bullet's semi-implicit Euler in 1 ms substeps is ahead by g t h / 2 = 1 mm.
  EXPECT_NEAR(pose.position.y(), 5.0 - 0.5 * 9.81 * t * t, 2e-3);
  EXPECT_NEAR(pose.velocity.y(), -9.81 * t, 1e-4);
  EXPECT_NEAR(pose.position.x(), 0.0f, 1e-6f);
  EXPECT_NEAR(pose.angular_velocity.norm(), 0.0f, 1e-6f);
}

TEST(RigidBodies, ForceAndTorqueGiveNewtonsAccelerations) {
  const Vec3f size(0.4f, 0.2f, 0.1f);
  RigidBodies bodies(SolidSet({box_at(Vec3f(0, 0, 0), size, 1000)}), Vec3f::Zero(), 0.005f);
  const double m = 1000.0 * 0.4 * 0.2 * 0.1;
  const double izz = m * (0.4 * 0.4 + 0.2 * 0.2) / 12.0;  // solid box about its z axis
  const double t = 0.1, torque = 0.02, force = 0.5;
  run(bodies, t, 0.002, {Vec3d(force, 0, 0)}, {Vec3d(0, 0, torque)});
  const BodyPose& pose = bodies.poses()[0];
  EXPECT_NEAR(pose.velocity.x(), force / m * t, 1e-5);
  EXPECT_NEAR(pose.angular_velocity.z(), torque / izz * t, 1e-4);
  // Turned about z by about alpha t^2 / 2 (semi-implicit Euler: within alpha t h / 2).
  const double angle = 2.0 * std::atan2(double(pose.orientation.z()), double(pose.orientation.w()));
  EXPECT_NEAR(angle, 0.5 * torque / izz * t * t, 0.5 * torque / izz * t * 0.001 + 1e-5);
}

// What a fluid solver's retry needs: put back at a pose it gave, a body moves on from it as it did
// the first time (in free flight; Bullet's emptied contact caches make contacts differ slightly).
TEST(RigidBodies, ResetToAnEarlierPoseRepeatsTheFlight) {
  RigidBodies bodies(SolidSet({box_at(Vec3f(0, 5, 0), Vec3f(0.2f, 0.1f, 0.3f), 700)}), Vec3f(0, -9.81f, 0), 0.005f);
  const std::vector<Vec3d> none = {Vec3d::Zero()};
  run(bodies, 0.05, 0.002, none, {Vec3d(0.1, 0.2, 0)});  // set it spinning
  const std::vector<BodyPose> earlier = bodies.poses();
  run(bodies, 0.1, 0.002, none, none);
  const BodyPose first = bodies.poses()[0];
  bodies.reset(earlier, 0.05);
  EXPECT_EQ(bodies.poses()[0].position, earlier[0].position);
  run(bodies, 0.1, 0.002, none, none);
  const BodyPose again = bodies.poses()[0];
  EXPECT_GT(first.angular_velocity.norm(), 0.1f);
  EXPECT_LT((again.position - first.position).norm(), 1e-5f);
  EXPECT_LT((again.velocity - first.velocity).norm(), 1e-5f);
  EXPECT_LT((again.angular_velocity - first.angular_velocity).norm(), 1e-4f);
  EXPECT_GT(std::abs(again.orientation.dot(first.orientation)), 1.0f - 1e-6f);
  EXPECT_THROW(bodies.reset({}, 0.0), Error);
}

TEST(RigidBodies, BoxComesToRestOnTheTankFloor) {
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(-1, 0, -1);
  tank.max = Vec3f(1, 1, 1);
  RigidBodies bodies(SolidSet({tank, box_at(Vec3f(0, 0.3f, 0), Vec3f(0.2f, 0.1f, 0.2f), 500)}),
                     Vec3f(0, -9.81f, 0), 0.005f);
  EXPECT_EQ(bodies.body_of_solid(0), -1);
  EXPECT_EQ(bodies.body_of_solid(1), 0);
  run(bodies, 1.0, 0.004, {Vec3d::Zero()}, {Vec3d::Zero()});
  const BodyPose& pose = bodies.poses()[0];
  EXPECT_NEAR(pose.position.y(), 0.05f, 1e-3f);  // bottom face on the floor
  EXPECT_NEAR(pose.velocity.norm(), 0.0f, 1e-3f);
  EXPECT_NEAR(std::abs(pose.orientation.w()), 1.0f, 1e-4f);
}

// Dropped from 0.25 m above the floor, a box comes to rest with its bottom face `skin` above the
// floor, and one from 0.3 m beside a static box rests on that box's top with the same gap.
TEST(RigidBodies, AFallingBoxLandsTheSkinAwayFromTheFloorAndStaticSolids) {
  const float skin = 0.02f;
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(-1, 0, -1);
  tank.max = Vec3f(1, 1, 1);
  Solid step;
  step.kind = Solid::Kind::Box;
  step.min = Vec3f(0.4f, 0, -0.2f), step.max = Vec3f(0.8f, 0.1f, 0.2f);
  RigidBodies bodies(SolidSet({tank, step, box_at(Vec3f(0, 0.3f, 0), Vec3f(0.2f, 0.1f, 0.2f), 500),
                               box_at(Vec3f(0.6f, 0.45f, 0), Vec3f(0.2f, 0.1f, 0.2f), 500)}),
                     Vec3f(0, -9.81f, 0), 0.005f, skin);
  run(bodies, 1.0, 0.004, {Vec3d::Zero(), Vec3d::Zero()}, {Vec3d::Zero(), Vec3d::Zero()});
  EXPECT_NEAR(bodies.poses()[0].position.y(), 0.05f + skin, 1e-3f);
  EXPECT_NEAR(bodies.poses()[1].position.y(), 0.1f + 0.05f + skin, 1e-3f);
  for (const BodyPose& pose : bodies.poses()) EXPECT_NEAR(pose.velocity.norm(), 0.0f, 1e-3f);
}

// A stack of three boxes placed on the floor (within the skin from the start) stays exactly where it
// was placed: pushed out of the skin, the bottom box would leap off the floor (3.6 m/s, measured
// before the bodies placed within it met the solids as they are).
TEST(RigidBodies, AStackPlacedOnTheFloorStaysWhereItWasPlaced) {
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(-1, 0, -1);
  tank.max = Vec3f(1, 1, 1);
  std::vector<Solid> solids{tank};
  for (int k = 0; k < 3; ++k) solids.push_back(box_at(Vec3f(0, 0.04f + 0.08f * k, 0), Vec3f::Constant(0.08f), 700));
  RigidBodies bodies(SolidSet(solids), Vec3f(0, -9.81f, 0), 0.005f, 0.02f);
  run(bodies, 0.5, 0.004, std::vector<Vec3d>(3, Vec3d::Zero()), std::vector<Vec3d>(3, Vec3d::Zero()));
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(bodies.poses()[size_t(k)].position.y(), 0.04f + 0.08f * k, 1e-4f) << k;
    EXPECT_NEAR(bodies.poses()[size_t(k)].velocity.norm(), 0.0f, 1e-3f) << k;
  }
}

TEST(RigidBodies, RejectsInvalidDynamicSolids) {
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.max = Vec3f(1, 1, 1);
  tank.dynamics.enabled = true;
  tank.dynamics.density = 500;
  EXPECT_THROW(RigidBodies(SolidSet({tank}), Vec3f::Zero(), 0.005f), Error);
  Solid massless = box_at(Vec3f::Zero(), Vec3f::Ones(), 0.0f);
  EXPECT_THROW(RigidBodies(SolidSet({massless}), Vec3f::Zero(), 0.005f), Error);
  Solid moving = box_at(Vec3f::Zero(), Vec3f::Ones(), 500.0f);
  moving.motion.kind = Motion::Kind::Sine;
  moving.motion.amplitude = 0.1f;
  EXPECT_THROW(RigidBodies(SolidSet({moving}), Vec3f::Zero(), 0.005f), Error);
}

}  // namespace
}  // namespace spume::fluid
