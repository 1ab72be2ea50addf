// A solver that blows up stops with an error naming the frame, the value and the bound, and leaves
// no record (so the stage is never taken for finished). The bounds (fluid/blow_up.h) are checked
// against hand-worked scene boxes, and a user's case, min_dt = max_dt = 1 s on the dam break
// (one step a frame), is run through the spume binary.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "sim/core/error.h"
#include "sim/fluid/blow_up.h"
#include "sim/io/stage_record.h"
#include "tests/stability/stability_support.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using stability::error_of;

Solid box_of(const Vec3f& lo, const Vec3f& hi, Solid::Kind kind = Solid::Kind::Box) {
  Solid s;
  s.kind = kind;
  s.min = lo, s.max = hi;
  return s;
}

const FluidBlock kBlock{Vec3f(0.1f, 0, 0.1f), Vec3f(0.5f, 0.6f, 0.5f)};

TEST(StabilityBlowUp, BoundsComeFromTheSceneBoxAndTheFastestSolid) {
  FluidSolverParams p;  // g = (0, -9.81, 0)
  const Solid tank = box_of(Vec3f(0, 0, 0), Vec3f(1, 1, 1), Solid::Kind::Tank);
  fluid::BlowUpLimits l = fluid::blow_up_limits(p, {kBlock}, SolidSet({tank}));
  EXPECT_FLOAT_EQ(float(l.height), 1.0f);
  EXPECT_FLOAT_EQ(float(l.bottom), 0.0f);
  EXPECT_NEAR(l.reference_speed, 4.42945, 1e-5);  // sqrt(2 * 9.81 * 1)
  EXPECT_NEAR(l.max_fall_speed, 22.1472, 1e-4);   // 5 x
  EXPECT_DOUBLE_EQ(l.max_density_error, 0.10);

  // A piston 0.5 m x 2 Hz: 2 pi m/s at most, 4 pi m/s thrown; its path widens the box, not its height.
  Solid piston = box_of(Vec3f(0, 0, 0), Vec3f(0.1f, 1, 1));
  piston.motion.kind = Motion::Kind::Sine;
  piston.motion.amplitude = 0.5f;
  piston.motion.frequency = 2.0f;
  l = fluid::blow_up_limits(p, {kBlock}, SolidSet({tank, piston}));
  EXPECT_NEAR(l.solid_speed, 2.0 * M_PI, 1e-5);
  EXPECT_NEAR(l.reference_speed, 4.0 * M_PI, 1e-5);
  EXPECT_FLOAT_EQ(float(l.height), 1.0f);

  // A lid keyframed up by 0.5 m in 2 s (0.25 m/s) raises the box's top to 1.5 m; a sphere reaching
  // 0.2 m below the floor lowers its bottom.
  Solid lid = box_of(Vec3f(0, 0.9f, 0), Vec3f(1, 1, 1));
  lid.motion.kind = Motion::Kind::Keyframes;
  lid.motion.times = {0.0, 2.0};
  lid.motion.offsets = {Vec3f::Zero(), Vec3f(0, 0.5f, 0)};
  Solid rock;
  rock.kind = Solid::Kind::Sphere;
  rock.center = Vec3f(0.5f, 0.1f, 0.5f);
  rock.radius = 0.3f;
  l = fluid::blow_up_limits(p, {kBlock}, SolidSet({tank, lid, rock}));
  EXPECT_NEAR(l.solid_speed, 0.25, 1e-6);
  EXPECT_NEAR(l.bottom, -0.2, 1e-6);
  EXPECT_NEAR(l.height, 1.7, 1e-6);
  EXPECT_NEAR(l.reference_speed, std::sqrt(2.0 * 9.81 * 1.7), 1e-5);

  // Gravity along -x: heights are measured along x.
  p.gravity = Vec3f(-2.0f, 0, 0);
  l = fluid::blow_up_limits(p, {kBlock}, SolidSet({box_of(Vec3f(0, 0, 0), Vec3f(3, 1, 1), Solid::Kind::Tank)}));
  EXPECT_FLOAT_EQ(float(l.height), 3.0f);
  EXPECT_NEAR(l.reference_speed, std::sqrt(2.0 * 2.0 * 3.0), 1e-6);
  // No gravity and nothing moving: the 1 m/s floor.
  p.gravity = Vec3f::Zero();
  l = fluid::blow_up_limits(p, {kBlock}, SolidSet({tank}));
  EXPECT_DOUBLE_EQ(l.reference_speed, 1.0);
  // A loose tolerance loosens the density bound with it.
  p.density_tolerance = 0.05f;
  EXPECT_NEAR(fluid::blow_up_limits(p, {kBlock}, SolidSet({tank})).max_density_error, 0.5, 1e-6);
}

TEST(StabilityBlowUp, FallSpeedCountsHeightSoFreeFallNeverTripsIt) {
  FluidSolverParams p;
  const fluid::BlowUpLimits l =
      fluid::blow_up_limits(p, {kBlock}, SolidSet({box_of(Vec3f(0, 0, 0), Vec3f(1, 1, 1), Solid::Kind::Tank)}));
  // 3 m/s at 0.5 m: sqrt(9 + 2 * 9.81 * 0.5) = sqrt(18.81).
  EXPECT_NEAR(fluid::fall_speed(l, Vec3f(0.3f, 0.5f, 0.2f), Vec3f(0, 3, 0)), std::sqrt(18.81), 1e-5);
  // Spilled over a wall and fallen 100 m below the floor from rest at its top: still sqrt(2 g 1 m).
  const double v = std::sqrt(2.0 * 9.81 * 101.0);
  EXPECT_NEAR(fluid::fall_speed(l, Vec3f(2, -100, 0), Vec3f(0, -float(v), 0)), std::sqrt(2.0 * 9.81), 1e-3);
}

fluid::Particles three_particles(const Vec3f& fast_velocity) {
  fluid::Particles p;
  p.resize(3);
  for (uint32_t i = 0; i < 3; ++i) {
    p.x[i] = Vec3f(0.2f + 0.1f * float(i), 0.1f, 0.2f);
    p.v[i] = Vec3f::Zero();
    p.id[i] = 10 + i;
  }
  p.v[1] = fast_velocity;
  return p;
}

TEST(StabilityBlowUp, CheckNamesTheParticleTheValueAndTheBound) {
  FluidSolverParams p;
  const fluid::BlowUpLimits l =
      fluid::blow_up_limits(p, {kBlock}, SolidSet({box_of(Vec3f(0, 0, 0), Vec3f(1, 1, 1), Solid::Kind::Tank)}));
  // At 0.1 m the bound 22.147 m/s on sqrt(v^2 + 2 g 0.1) allows |v| up to sqrt(22.147^2 - 1.962) = 22.103.
  EXPECT_NO_THROW(fluid::check_blow_up(l, p, three_particles(Vec3f(22.09f, 0, 0)), 0.0005, 0.5));
  const std::string fast = error_of([&] { fluid::check_blow_up(l, p, three_particles(Vec3f(0, 22.12f, 0)), 0.0005, 0.5); });
  for (const char* part : {"blew up at t = 0.5 s", "particle 11 moves at 22.12 m/s", "bound 22.147", "H = 1 m",
                           "fluid.solver.max_dt (now 0.005 s)", "fluid.solver.depth_cfl (now 0.55)",
                           "fluid.solver.cfl (now 0.4)"})
    EXPECT_NE(fast.find(part), std::string::npos) << part << " not in: " << fast;
  // The walls' pressure is named only where it is not already the extrapolated one.
  EXPECT_EQ(fast.find("wall_pressure"), std::string::npos) << fast;
  FluidSolverParams own = p;
  own.extrapolate_wall_pressure = false;
  const std::string churn = error_of([&] { fluid::check_blow_up(l, own, three_particles(Vec3f(0, 22.12f, 0)), 0.0005, 0.5); });
  EXPECT_NE(churn.find("wall_pressure = extrapolated"), std::string::npos) << churn;

  EXPECT_NO_THROW(fluid::check_blow_up(l, p, three_particles(Vec3f::Zero()), 0.0999, 0.5));
  const std::string dense = error_of([&] { fluid::check_blow_up(l, p, three_particles(Vec3f::Zero()), 1.72, 0.5); });
  for (const char* part : {"compression after the density solve is 172%", "above the bound 10%", "0.05%"})
    EXPECT_NE(dense.find(part), std::string::npos) << part << " not in: " << dense;
  // NaN never passes.
  EXPECT_FALSE(error_of([&] { fluid::check_blow_up(l, p, three_particles(Vec3f::Zero()), NAN, 0.5); }).empty());
}

// A user's case: the dam break (scenes/dambreak.json's fluid and tank) with min_dt = max_dt = 1 s,
// so every 1/30 s frame is one step. Measured: speeds 0.5, 0.8, 2.0, 7.9, 4.3, 21 m/s in frames 1-6,
// then 104 m/s at frame 7 (beyond 5 x sqrt(2 g 1 m) = 22.1 m/s), NaN at frame 10 without the check.
// The stage's record (saved as the run goes) never reaches the frame that blew up.
TEST(StabilityBlowUp, OneStepFramesStopTheDamBreakAtFrameSevenRecordingOnlyHealthyFrames) {
  const testing::TempDir temp;
  const std::filesystem::path& dir = temp.path;
  std::ofstream(dir / "dambreak.json") << R"({
    "name": "dambreak",
    "fluid": {"source": "solver", "radius": 0.0093, "fps": 30, "frames": [0, 90],
              "blocks": [{"min": [0.0, 0.0, 0.0], "max": [0.4, 0.8, 0.6]}]},
    "solids": [{"type": "tank", "min": [0, 0, 0], "max": [1.6, 1.0, 0.6]}]
  })";
  const testing::CommandResult r =
      testing::run_spume("simulate " + (dir / "dambreak.json").string() + " --frames 0-20 --out " +
                         (dir / "out").string() + " --quiet --set fluid.solver.min_dt=1 --set fluid.solver.max_dt=1");
  EXPECT_EQ(r.status, 1) << r.output;
  for (const char* part : {"fluid frame 7 (t = 0.2", "blew up", "bound 22.147", "fluid.solver.max_dt (now 1 s)"})
    EXPECT_NE(r.output.find(part), std::string::npos) << part << " not in: " << r.output;
  const std::optional<StageRecord> record = read_stage_record(dir / "out/dambreak/fluid");
  if (record) {
    EXPECT_LE(record->last_frame, 6);
  }
  EXPECT_TRUE(fs::exists(dir / "out/dambreak/fluid/fluid_0006.spf"));  // the frames before it were healthy
  EXPECT_FALSE(fs::exists(dir / "out/dambreak/fluid/fluid_0007.spf"));
  EXPECT_FALSE(fs::exists(dir / "out/dambreak/diffuse"));  // nothing downstream ran
}

}  // namespace
}  // namespace spume
