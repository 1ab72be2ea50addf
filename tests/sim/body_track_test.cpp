// The dynamic solids' track: the fluid stage writes the solver's body poses per frame, they read back
// bit for bit, poses between frames interpolate (linear centre, slerped orientation), and the diffuse
// stage and renderer see the bodies where the solver put them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "sim/core/error.h"
#include "sim/fluid/solver.h"
#include "sim/stage/body_track_file.h"
#include "sim/stage/simulate_scene.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

BodyPose pose(uint32_t solid, Vec3f position, Quatf orientation, Vec3f velocity = Vec3f::Zero()) {
  BodyPose p;
  p.solid = solid;
  p.position = position;
  p.orientation = orientation;
  p.velocity = velocity;
  return p;
}

TEST(BodyTrack, InterpolatesCentresLinearlyAndOrientationsAlongTheShortArc) {
  BodyTrack track;
  track.fps = 10.0;
  track.first_frame = 2;
  const Quatf quarter_turn(Eigen::AngleAxisf(float(M_PI / 2), Vec3f::UnitZ()));
  track.frames = {{pose(1, Vec3f(0, 1, 0), Quatf::Identity(), Vec3f(1, 0, 0))},
                  {pose(1, Vec3f(2, 1, 0), quarter_turn, Vec3f(3, 0, 0))}};
  // At 10 fps, t = 0.25 s lies half way between frame 2 (0.2 s) and frame 3 (0.3 s).
  const std::vector<BodyPose> mid = track.at_time(0.25);
  ASSERT_EQ(mid.size(), 1u);
  EXPECT_EQ(mid[0].solid, 1u);
  EXPECT_NEAR(mid[0].position.x(), 1.0f, 1e-6f);
  EXPECT_NEAR(mid[0].velocity.x(), 2.0f, 1e-6f);
  // Half of a quarter turn about z: 45 degrees.
  const Quatf expected(Eigen::AngleAxisf(float(M_PI / 4), Vec3f::UnitZ()));
  EXPECT_NEAR(std::abs(mid[0].orientation.dot(expected)), 1.0f, 1e-6f);
  // Outside the track: clamped to its ends.
  EXPECT_EQ(track.at_time(0.0)[0].position, Vec3f(0, 1, 0));
  EXPECT_EQ(track.at_time(9.0)[0].position, Vec3f(2, 1, 0));
}

TEST(BodyTrackFile, RoundTripsEveryFloatExactly) {
  const testing::TempDir temp;
  const fs::path& dir = temp.path;
  BodyTrack track;
  track.fps = 24.0;
  track.first_frame = 0;
  const Quatf q = Quatf(0.3f, -0.5f, 0.7f, 0.1f).normalized();
  for (int f = 0; f < 3; ++f)
    track.frames.push_back({pose(0, Vec3f(0.1f * f, 1.0f / 3.0f, -2e-7f), q, Vec3f(1e-9f, 123.456f, -7.0f)),
                            pose(4, Vec3f(1.0f / 7.0f, 2.0f, 3.0f), Quatf::Identity())});
  track.frames[2][0].angular_velocity = Vec3f(0.1f, 0.2f, 0.3f);
  write_body_track(dir / "bodies.csv", track);
  const BodyTrack back = read_body_track(dir / "bodies.csv", 24.0);
  ASSERT_EQ(back.frames.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    ASSERT_EQ(back.frames[k].size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
      const BodyPose& a = track.frames[k][i];
      const BodyPose& b = back.frames[k][i];
      EXPECT_EQ(a.solid, b.solid);
      EXPECT_EQ(a.position, b.position);
      EXPECT_EQ(a.orientation.coeffs(), b.orientation.coeffs());
      EXPECT_EQ(a.velocity, b.velocity);
      EXPECT_EQ(a.angular_velocity, b.angular_velocity);
    }
  }
}

void expect_read_error(const std::string& text, const std::string& expected) {
  const testing::TempDir temp;
  const fs::path& dir = temp.path;
  std::ofstream(dir / "bodies.csv") << text;
  try {
    read_body_track(dir / "bodies.csv", 30.0);
    ADD_FAILURE() << "accepted: " << text;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bodies.csv"), std::string::npos) << e.what();
  }
}

TEST(BodyTrackFile, MalformedFilesAreRefusedNamingTheLine) {
  const std::string header = "frame,solid,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  expect_read_error("", "header");
  expect_read_error(header, "no rows");
  expect_read_error(header + "0,0,1,2,3,1,0,0,0,0,0,0,0,0\n", "line 2: 14 columns");
  expect_read_error(header + "0,0,1,2,nan,1,0,0,0,0,0,0,0,0,0\n", "line 2: column 5");
  expect_read_error(header + "0,0,1,2,3,2,0,0,0,0,0,0,0,0,0\n", "unit quaternion");
  expect_read_error(header + "0,0,1,2,3,1,0,0,0,0,0,0,0,0,0\n2,0,1,2,3,1,0,0,0,0,0,0,0,0,0\n", "out of order");
  expect_read_error(header + "0,0,1,2,3,1,0,0,0,0,0,0,0,0,0\n1,1,1,2,3,1,0,0,0,0,0,0,0,0,0\n", "other bodies");
}

// A heavy cube above a shallow pool, frames 0-3 at 20 fps.
Json cube_over_a_pool() {
  return Json::parse(R"({
    "name": "drop",
    "fluid": {"source": "solver", "radius": 0.025, "fps": 20, "frames": [0, 3],
              "blocks": [{"min": [0.0, 0.0, 0.0], "max": [0.4, 0.1, 0.4]}]},
    "solids": [{"type": "tank", "min": [0, 0, 0], "max": [0.4, 0.6, 0.4]},
               {"type": "box", "min": [0.15, 0.3, 0.15], "max": [0.25, 0.4, 0.25], "dynamic": {"density": 2000}}]
  })");
}

// The cube dropped into the pool: the stage's track holds the solver's poses at every frame time,
// and the cube falls.
TEST(BodyTrackStage, FluidStageWritesTheSolversPosesPerFrame) {
  const testing::TempDir temp;
  const fs::path& out = temp.path;
  const ParamReader root = ParamReader::from_json(cube_over_a_pool(), "drop.json");
  const SimScene scene = read_sim_scene(root, ".", "drop");
  DiffuseStageOptions options;
  options.out_root = out;
  options.quiet = true;
  simulate_scene(scene, options);

  const BodyTrack track = scene_body_track(scene, out / "drop");
  ASSERT_EQ(track.frames.size(), 4u);
  FluidSolver reference(scene.solver.params, scene.solver.blocks, scene.solids);
  for (int f = 0; f <= 3; ++f) {
    reference.advance_to(f / 20.0);
    ASSERT_EQ(track.frames[size_t(f)].size(), 1u);
    EXPECT_EQ(track.frames[size_t(f)][0].solid, 1u);
    EXPECT_EQ(track.frames[size_t(f)][0].position, reference.body_poses()[0].position) << "frame " << f;
  }
  EXPECT_FLOAT_EQ(track.frames[0][0].position.y(), 0.35f);
  // Free fall for 0.15 s would drop it 0.11 m; it must at least have fallen.
  EXPECT_LT(track.frames[3][0].position.y(), 0.34f);
  const SolidSet at_end = solids_at_time(scene.solids, track, 3 / 20.0);
  // The box is stored as min/max about its centre, so the centre comes back to float rounding.
  EXPECT_LT((at_end.solids()[1].centre() - track.frames[3][0].position).norm(), 1e-6f);
}

// The bodies' skin (fluid/rigid_bodies.h), then Bullet started afresh every frame, changed how solver
// scenes with dynamic bodies move, so their fluid keys carry a generation of their own: caches made
// before it are stale, while a scene without bodies keeps its caches.
TEST(BodyTrackStage, OnlyScenesWithBodiesCarryTheBodiesGeneration) {
  Json json = cube_over_a_pool();
  const SimScene with_body = read_sim_scene(ParamReader::from_json(json, "drop.json"), ".", "drop");
  EXPECT_EQ(with_body.fluid_keys.value("spume_bodies_generation", 0), 3);
  json["solids"][1].erase("dynamic");
  const SimScene without = read_sim_scene(ParamReader::from_json(json, "drop.json"), ".", "drop");
  EXPECT_FALSE(without.fluid_keys.contains("spume_bodies_generation"));
}

TEST(BodyTrackStage, DynamicSolidsWithAFileFluidAreRefused) {
  const Json json = Json::parse(R"({
    "name": "files", "fluid": {"files": "nothing_%d.bgeo", "radius": 0.02},
    "solids": [{"type": "box", "min": [0, 0, 0], "max": [0.1, 0.1, 0.1], "dynamic": {"density": 500}}]
  })");
  const ParamReader root = ParamReader::from_json(json, "files.json");
  const SimScene scene = read_sim_scene(root, ".", "files");
  try {
    scene_body_track(scene, "out/files");
    ADD_FAILURE() << "accepted dynamic solids without the solver";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fluid.source"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace spume
