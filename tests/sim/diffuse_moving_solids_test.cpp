// Diffuse particles and kinematic solids: every step sees the solids where they are at its time.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sim/diffuse/simulator.h"
#include "sim/scene/diffuse_params_reader.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

constexpr double kFps = 50.0;

DiffuseSetup still_air_setup(const Solid& solid) {
  DiffuseSetup s;
  s.fluid.particle_radius = 0.02f;
  s.fluid.support_radius = 0.08f;
  s.fluid.fps = kFps;
  s.params = read_diffuse_params(ParamReader::from_json(Json::object(), "test"), s.fluid, Vec3f(0, -9.81f, 0));
  // No gravity and no fluid near the particles: whatever their type, they keep their velocity, so
  // any motion comes from the solid.
  s.params.gravity = Vec3f::Zero();
  s.params.k_ta = s.params.k_wc = 0.0f;
  s.solids = SolidSet({solid});
  return s;
}

// A fluid of one resting particle far from everything, frame k at time k / fps.
std::vector<FluidFrame> distant_fluid(int frames) {
  std::vector<FluidFrame> fluid;
  for (int k = 0; k < frames; ++k) fluid.push_back(testing::frame_of(k, k / kFps, {Vec3f(5, 5, 5)}, {Vec3f::Zero()}));
  return fluid;
}

Solid box_keyframed(const Vec3f& lo, const Vec3f& hi, std::vector<double> times, std::vector<Vec3f> offsets) {
  Solid box;
  box.kind = Solid::Kind::Box;
  box.min = lo, box.max = hi;
  box.motion.kind = Motion::Kind::Keyframes;
  box.motion.times = std::move(times);
  box.motion.offsets = std::move(offsets);
  return box;
}

TEST(DiffuseMovingSolids, BoxSweepingThroughACloudPushesItAtTheWallsSpeed) {
  // The box [-0.1, 0.1]^3 moves +x at 1 m/s from t = 0 to 0.5 s, then stops with its front at x = 0.6.
  const Solid box = box_keyframed(Vec3f::Constant(-0.1f), Vec3f::Constant(0.1f), {0.0, 0.5},
                                  {Vec3f::Zero(), Vec3f(0.5f, 0, 0)});
  const float wall_speed = 1.0f;
  DiffuseSimulator sim(still_air_setup(box));
  // A resting cloud ahead of the box, wider than its cross-section (|y|, |z| up to 0.15). Its x
  // values sit 0.005 m or more from every step's face position (0.1 + 0.02 k), so no particle is
  // ambiguously on the face.
  DiffuseFrame cloud;
  std::vector<Vec3f> start;
  for (float x = 0.125f; x < 0.49f; x += 0.03f)
    for (float y = -0.15f; y < 0.151f; y += 0.03f)
      for (float z = -0.15f; z < 0.151f; z += 0.03f) start.push_back(Vec3f(x, y, z));
  cloud.resize(start.size());
  for (size_t i = 0; i < start.size(); ++i) {
    cloud.positions[i] = start[i];
    cloud.velocities[i] = Vec3f::Zero();
    cloud.lifetimes[i] = 100.0f;
    cloud.ids[i] = i;
  }
  sim.set_particles(cloud);

  const auto fluid = distant_fluid(31);
  size_t pushed_during_motion = 0;
  for (int k = 0; k + 1 < int(fluid.size()); ++k) {
    sim.process_frame(fluid[k], &fluid[k + 1], [](const DiffuseFrame&, const FrameStats&) {});
    const double t = fluid[k + 1].time;
    const SolidSet solids_now = SolidSet({box}).at_time(t);
    const float front = 0.1f + std::min(float(t), 0.5f);  // the box's +x face at t
    const DiffuseFrame& d = sim.particles();
    ASSERT_EQ(d.size(), start.size());  // nothing dissolves or leaves (no domain)
    for (size_t i = 0; i < d.size(); ++i) {
      const Vec3f& p = d.positions[i];
      const Vec3f& x0 = start[d.ids[i]];
      ASSERT_FALSE(solids_now.inside(p)) << "particle " << d.ids[i] << " inside the box at t = " << t;
      // Within a step the face overtakes a particle by at most 0.015 m; those 0.03 m or more from
      // the side faces are pushed out through the front face, nearer ones may leave through a side.
      const float off_axis = std::max(std::abs(x0.y()), std::abs(x0.z()));
      if (off_axis >= 0.07f && off_axis <= 0.1f) continue;
      if (off_axis < 0.07f && x0.x() < front) {
        // Reached by the face: moving at least as fast as the wall along its normal (+x), and
        // carried along in front of it (after the box stops, coasting at that speed).
        ASSERT_GE(d.velocities[i].x(), wall_speed - 1e-5f) << d.ids[i] << " at t = " << t;
        const float expected_x = t <= 0.5 ? front : 0.6f + wall_speed * float(t - 0.5);
        ASSERT_NEAR(p.x(), expected_x, 1e-4f) << d.ids[i] << " at t = " << t;
        if (t <= 0.5) ++pushed_during_motion;
      } else {
        // Out of the box's path, or not reached yet: untouched.
        ASSERT_EQ(d.velocities[i], Vec3f::Zero()) << d.ids[i] << " at t = " << t;
        ASSERT_EQ(p, x0) << d.ids[i] << " at t = " << t;
      }
    }
  }
  EXPECT_GT(pushed_during_motion, 1000u);  // the check above ran on many particles
}

TEST(DiffuseMovingSolids, ClassificationCountsTheSolidWhereItIsAtTheFramesTime) {
  // The box starts 1 m away and arrives at t = 0.2 s with its +x face 0.01 m from the particle, which
  // sits in a wet gap: a resting lattice of water (spacing 0.04 m) starts 0.01 m on its other side.
  const Solid box = box_keyframed(Vec3f::Constant(-0.1f), Vec3f::Constant(0.1f), {0.0, 0.2},
                                  {Vec3f(-1, 0, 0), Vec3f(0.1f, 0, 0)});
  DiffuseSimulator sim(still_air_setup(box));
  DiffuseFrame one;
  one.resize(1);
  one.positions[0] = Vec3f(0.21f, 0, 0);
  one.velocities[0] = Vec3f::Zero();
  one.lifetimes[0] = 100.0f;
  one.ids[0] = 0;
  sim.set_particles(one);
  // Within h = 0.08 of the particle: 9 lattice points in the plane x = 0.22 (i^2 + k^2 <= 3.94 in
  // spacings) and 9 in x = 0.26 (<= 2.43): 18, foam. The box's face 0.01 m away covers the cap
  // (h - d)^2 (2h + d) / (4 h^3) = 0.4067 of the ball, so the wet wall makes 18 / 0.5933 = 30.3: a bubble.
  const auto water = testing::lattice(Vec3f(0.22f, -0.32f, -0.32f), Vec3f(0.5f, 0.32f, 0.32f), 0.04f);
  std::vector<FluidFrame> fluid;
  for (int k = 0; k < 12; ++k)
    fluid.push_back(testing::frame_of(k, k / kFps, water, std::vector<Vec3f>(water.size(), Vec3f::Zero())));
  std::vector<DiffuseType> types;
  for (int k = 0; k + 1 < int(fluid.size()); ++k)
    sim.process_frame(fluid[k], &fluid[k + 1],
                      [&](const DiffuseFrame& f, const FrameStats&) { types.push_back(f.types[0]); });
  EXPECT_EQ(types[0], DiffuseType::Foam);     // the box is 1 m away
  EXPECT_EQ(types[10], DiffuseType::Bubble);  // t = 0.2: the box's face is 0.01 m away
  EXPECT_EQ(sim.particles().positions[0], Vec3f(0.21f, 0, 0));  // never touched
}

}  // namespace
}  // namespace spume
