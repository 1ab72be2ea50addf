// Stored velocities against the fluid's motion (scene/velocity_check.h), on surveys of a block falling
// freely worked by hand: centroid y(t) = 1 - g t^2 / 2, mean velocity -g t. Over [t, t + dt] the
// centroid moves at -g (t + dt/2), exactly the mean of the two frames' velocities, so the ratio is 1.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/scene/velocity_check.h"

namespace spume {
namespace {

constexpr double kFps = 25.0;
constexpr float kG = 9.81f;
constexpr float kRadius = 0.01f;

// Frames 0..10 of a block of `particles` particles (times `growth` per frame) falling from rest, its
// stored velocities multiplied by `units`.
FluidSurvey falling_block(float units, double growth = 1.0, uint64_t particles = 1000) {
  FluidSurvey survey;
  double n = double(particles);
  for (int k = 0; k <= 10; ++k) {
    const float t = float(k / kFps);
    FrameSurvey f;
    f.frame = k;
    f.particles = uint64_t(n);
    f.centroid = Vec3f(0.3f, 1.0f - 0.5f * kG * t * t, 0.2f);
    f.mean_velocity = Vec3f(0.0f, -kG * t * units, 0.0f);
    survey.frames.push_back(f);
    n *= growth;
  }
  return survey;
}

TEST(VelocityCheck, VelocitiesInSecondsAndMetresAgreeWithTheMotion) {
  const VelocityCheck c = check_stored_velocities(falling_block(1.0f), kFps, kRadius, 1.0f);
  // The first interval moves the centroid g dt^2 / 2 = 7.8 mm = 0.78 r, above r/10: every interval counts.
  EXPECT_EQ(c.intervals, 10);
  EXPECT_NEAR(c.ratio, 1.0f, 1e-3f);
  EXPECT_EQ(c.note.rfind("stored velocities agree with the motion", 0), 0u) << c.note;
}

TEST(VelocityCheck, GridUnitsAreMeasuredAndTheScaleThatFixesThemIsNamed) {
  // Mantaflow-like: velocities 12.7 times too large.
  const VelocityCheck c = check_stored_velocities(falling_block(12.7f), kFps, kRadius, 1.0f);
  EXPECT_NEAR(c.ratio, 12.7f, 0.02f);
  EXPECT_EQ(c.note.rfind("warning: the stored velocities are 12.7", 0), 0u) << c.note;
  EXPECT_NE(c.note.find("fluid.velocity_scale = 0.0787"), std::string::npos) << c.note;  // 1 / 12.7
  // With that scale they agree.
  const VelocityCheck fixed = check_stored_velocities(falling_block(12.7f), kFps, kRadius, 1.0f / 12.7f);
  EXPECT_NEAR(fixed.ratio, 1.0f, 1e-3f);
  EXPECT_NE(fixed.note.find("agree"), std::string::npos) << fixed.note;
  EXPECT_NE(fixed.note.find("after fluid.velocity_scale"), std::string::npos) << fixed.note;
}

TEST(VelocityCheck, AWrongFrameRateIsMeasuredAndTheRateThatFixesItIsNamed) {
  // Frames written at 25 per second, read as 50: the motion looks twice as fast as the velocities.
  const VelocityCheck c = check_stored_velocities(falling_block(1.0f), 2 * kFps, kRadius, 1.0f);
  EXPECT_NEAR(c.ratio, 0.5f, 1e-3f);
  EXPECT_NE(c.note.find("set fluid.fps (--fps) to 25"), std::string::npos) << c.note;
}

TEST(VelocityCheck, AFluidAtRestOrOneThatChangesItsCountMeasuresNothing) {
  FluidSurvey rest = falling_block(1.0f);
  for (FrameSurvey& f : rest.frames) f.centroid = Vec3f(0.3f, 1.0f, 0.2f), f.mean_velocity = Vec3f(0.01f, 0, 0);
  const VelocityCheck at_rest = check_stored_velocities(rest, kFps, kRadius, 1.0f);
  EXPECT_EQ(at_rest.intervals, 0);
  EXPECT_TRUE(std::isnan(at_rest.ratio));
  EXPECT_EQ(at_rest.note.rfind("stored velocities not checked", 0), 0u) << at_rest.note;
  // An emitter adding 0.6% of its particles a frame: its centroid moves by where they are added.
  const VelocityCheck growing = check_stored_velocities(falling_block(12.7f, 1.006), kFps, kRadius, 1.0f);
  EXPECT_EQ(growing.intervals, 0);
  // Without stored velocities there is nothing to check and nothing to say.
  FluidSurvey bare = falling_block(1.0f);
  for (FrameSurvey& f : bare.frames) f.mean_velocity = Vec3f::Constant(NAN);
  EXPECT_EQ(check_stored_velocities(bare, kFps, kRadius, 1.0f).note, "");
}

}  // namespace
}  // namespace spume
