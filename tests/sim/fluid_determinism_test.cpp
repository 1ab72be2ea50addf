// The solver's result must not depend on the number of threads: byte-identical state after N steps.
#include <gtest/gtest.h>

#include <cstring>

#include "sim/core/parallel.h"
#include "sim/fluid/solver.h"

namespace spume {
namespace {

// A tank from the origin to `max`.
Solid tank_to(const Vec3f& max) {
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(0, 0, 0);
  tank.max = max;
  return tank;
}

template <typename A>
bool same_bytes(const A& a, const A& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
}

FluidFrame run(int threads, bool extrapolate_wall_pressure = false) {
  set_thread_count(threads);
  FluidSolverParams p;
  p.particle_radius = 0.01f;
  p.extrapolate_wall_pressure = extrapolate_wall_pressure;
  p.xsph = 0.05f;  // exercise every term
  const Solid tank = tank_to(Vec3f(0.6f, 0.4f, 0.2f));
  Solid sphere;
  sphere.kind = Solid::Kind::Sphere;
  sphere.center = Vec3f(0.45f, 0.05f, 0.1f);
  sphere.radius = 0.06f;
  Solid paddle;
  paddle.kind = Solid::Kind::Box;
  paddle.min = Vec3f(0.55f, 0.0f, 0.0f);
  paddle.max = Vec3f(0.6f, 0.3f, 0.2f);
  paddle.motion.kind = Motion::Kind::Keyframes;
  paddle.motion.times = {0.0, 0.2};
  paddle.motion.offsets = {Vec3f::Zero(), Vec3f(-0.05f, 0, 0)};
  FluidSolver solver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(0.2f, 0.3f, 0.2f)}}, SolidSet({tank, sphere, paddle}));
  for (int i = 0; i < 40; ++i) solver.step();
  FluidFrame f = solver.frame(0);
  const std::vector<float> rho = solver.density_ratios();
  f.masses = rho;  // compare densities too
  return f;
}

// A tilted floating box and a sinking sphere (two-way coupled, Bullet) in a small tank.
struct BodyRun {
  FluidFrame frame;
  std::vector<BodyPose> poses;
};

BodyRun run_with_bodies(int threads, bool extrapolate_wall_pressure = false) {
  set_thread_count(threads);
  FluidSolverParams p;
  p.particle_radius = 0.01f;
  p.extrapolate_wall_pressure = extrapolate_wall_pressure;
  const Solid tank = tank_to(Vec3f(0.4f, 0.4f, 0.3f));
  Solid box;
  box.kind = Solid::Kind::Box;
  box.min = Vec3f(0.05f, 0.2f, 0.08f);
  box.max = Vec3f(0.2f, 0.26f, 0.2f);
  box.orientation = Quatf(Eigen::AngleAxisf(0.3f, Vec3f(0.3f, 0.2f, 1.0f).normalized()));
  box.dynamics.enabled = true;
  box.dynamics.density = 600.0f;
  Solid ball;
  ball.kind = Solid::Kind::Sphere;
  ball.center = Vec3f(0.3f, 0.25f, 0.15f);
  ball.radius = 0.04f;
  ball.dynamics.enabled = true;
  ball.dynamics.mass = 0.5f;
  FluidSolver solver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(0.4f, 0.18f, 0.3f)}}, SolidSet({tank, box, ball}));
  for (int i = 0; i < 40; ++i) solver.step();
  return {solver.frame(0), solver.body_poses()};
}

TEST(FluidDeterminism, OneAndTwoThreadsGiveByteIdenticalStatesWithDynamicBodies) {
  const BodyRun one = run_with_bodies(1);
  const BodyRun two = run_with_bodies(2);
  set_thread_count(0);
  ASSERT_EQ(one.frame.size(), two.frame.size());
  EXPECT_EQ(one.frame.time, two.frame.time);
  EXPECT_TRUE(same_bytes(one.frame.positions, two.frame.positions));
  EXPECT_TRUE(same_bytes(one.frame.velocities, two.frame.velocities));
  ASSERT_EQ(one.poses.size(), 2u);
  ASSERT_EQ(two.poses.size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(one.poses[k].position, two.poses[k].position);
    EXPECT_EQ(one.poses[k].orientation.coeffs(), two.poses[k].orientation.coeffs());
    EXPECT_EQ(one.poses[k].angular_velocity, two.poses[k].angular_velocity);
  }
  // The bodies did move (fell, and the box turned).
  EXPECT_LT(one.poses[1].position.y(), 0.25f - 0.01f);
  EXPECT_GT(one.poses[0].angular_velocity.norm(), 0.0f);
}

TEST(FluidDeterminism, OneAndTwoThreadsGiveByteIdenticalStates) {
  const FluidFrame one = run(1);
  const FluidFrame two = run(2);
  const FluidFrame again = run(2);
  set_thread_count(0);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_GT(one.time, 0.0);
  EXPECT_EQ(one.time, two.time);
  EXPECT_TRUE(same_bytes(one.positions, two.positions));
  EXPECT_TRUE(same_bytes(one.velocities, two.velocities));
  EXPECT_TRUE(same_bytes(one.masses, two.masses));
  EXPECT_TRUE(same_bytes(two.positions, again.positions));
}

// The wall pressure extrapolated from the fluid (boundary_pressure.h): its lists are transposed in
// fluid order and each wall particle sums its own neighbours, so the thread count cannot show.
TEST(FluidDeterminism, OneAndTwoThreadsGiveByteIdenticalStatesWithExtrapolatedWallPressure) {
  const FluidFrame one = run(1, true);
  const FluidFrame two = run(2, true);
  const BodyRun bodies_one = run_with_bodies(1, true);
  const BodyRun bodies_two = run_with_bodies(2, true);
  const FluidFrame own = run(2, false);
  set_thread_count(0);
  EXPECT_TRUE(same_bytes(one.positions, two.positions));
  EXPECT_TRUE(same_bytes(one.velocities, two.velocities));
  EXPECT_TRUE(same_bytes(one.masses, two.masses));
  EXPECT_TRUE(same_bytes(bodies_one.frame.positions, bodies_two.frame.positions));
  ASSERT_EQ(bodies_one.poses.size(), bodies_two.poses.size());
  for (size_t k = 0; k < bodies_one.poses.size(); ++k) {
    EXPECT_EQ(bodies_one.poses[k].position, bodies_two.poses[k].position);
    EXPECT_EQ(bodies_one.poses[k].orientation.coeffs(), bodies_two.poses[k].orientation.coeffs());
  }
  EXPECT_FALSE(same_bytes(one.positions, own.positions));  // the choice did take effect
}

// 74k particles in 145 chunks, the fused sweep of the pressure solves cut into one part per thread
// (fused_sweep.h) with many chunks whose neighbours reach across the cut: those are finished last.
TEST(FluidDeterminism, OneAndTwoThreadsGiveByteIdenticalStatesWhenTheSweepIsSplit) {
  auto run_large = [](int threads) {
    set_thread_count(threads);
    FluidSolverParams p;
    p.particle_radius = 0.005f;
    const Solid tank = tank_to(Vec3f(0.8f, 0.6f, 0.42f));
    FluidSolver solver(p, {FluidBlock{Vec3f(0, 0, 0), Vec3f(0.42f, 0.42f, 0.42f)}}, SolidSet({tank}));
    for (int i = 0; i < 8; ++i) solver.step();
    FluidFrame f = solver.frame(0);
    f.masses = solver.density_ratios();
    return f;
  };
  const FluidFrame one = run_large(1);
  const FluidFrame two = run_large(2);
  set_thread_count(0);
  ASSERT_GT(one.size(), 2u * 8u * 512u);  // two parts of at least 8 chunks
  EXPECT_TRUE(same_bytes(one.positions, two.positions));
  EXPECT_TRUE(same_bytes(one.velocities, two.velocities));
  EXPECT_TRUE(same_bytes(one.masses, two.masses));
}

}  // namespace
}  // namespace spume
