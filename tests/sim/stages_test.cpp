// The simulation stages on disk: the solver scene's fluid caches sample the solver at frame times,
// current caches are reused without running anything, and a changed key or a missing frame makes a
// stage run again.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sim/fluid/solver.h"
#include "sim/io/spume_cache.h"
#include "sim/stage/cache_state.h"
#include "sim/stage/fluid_stage.h"
#include "sim/stage/simulate_scene.h"
#include "tests/support/csv.h"
#include "tests/support/temp_dir.h"
#include "tests/support/written_files.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

// A 0.2 m cube of water (r = 0.025: 64 particles) falling in a tank, 4 frames at 20 fps.
Json tiny_solver_scene() {
  return Json::parse(R"({
    "name": "tiny",
    "fluid": {"source": "solver", "radius": 0.025, "fps": 20, "frames": [0, 3],
              "blocks": [{"min": [0.1, 0.1, 0.1], "max": [0.3, 0.3, 0.3]}]},
    "solids": [{"type": "tank", "min": [0, 0, 0], "max": [0.4, 0.6, 0.4]}]
  })");
}

SimScene scene_of(const Json& json) {
  const ParamReader root = ParamReader::from_json(json, "tiny.json");
  SimScene scene = read_sim_scene(root, ".", "tiny");
  root.reject_unknown_keys();
  return scene;
}

class PipelineStages : public ::testing::Test {
 protected:
  void SetUp() override {
    options.out_root = out;
    options.quiet = true;
  }
  const testing::TempDir temp;
  const fs::path& out = temp.path;
  DiffuseStageOptions options;
};

TEST_F(PipelineStages, FluidCachesHoldTheSolverStateAtEachFrameTime) {
  const SimScene scene = scene_of(tiny_solver_scene());
  const SceneSimulation result = simulate_scene(scene, options);
  EXPECT_FALSE(result.fluid.reused);
  EXPECT_EQ(result.fluid.frames, 4);
  EXPECT_EQ(result.diffuse.frames, 4);

  // The same solver stepped by hand to t = k / 20 s gives the same bytes.
  FluidSolver reference(scene.solver.params, scene.solver.blocks, scene.solids);
  ASSERT_EQ(reference.size(), 64u);
  for (int k = 0; k <= 3; ++k) {
    reference.advance_to(k / 20.0);
    const FluidFrame expected = reference.frame(k);
    FluidCacheHeader header;
    const FluidFrame cached = read_fluid_cache(fluid_cache_path(out / "tiny", k), &header);
    EXPECT_EQ(cached.index, k);
    EXPECT_DOUBLE_EQ(cached.time, k / 20.0);
    EXPECT_FLOAT_EQ(header.particle_radius, 0.025f);
    ASSERT_EQ(cached.size(), 64u);
    EXPECT_EQ(cached.positions, expected.positions) << "frame " << k;
    EXPECT_EQ(cached.velocities, expected.velocities) << "frame " << k;
    EXPECT_EQ(cached.ids, expected.ids);
    EXPECT_TRUE(fs::is_regular_file(diffuse_cache_path(out / "tiny", k)));
  }
  EXPECT_TRUE(fs::is_regular_file(out / "tiny/fluid/solver_stats.csv"));
}

TEST_F(PipelineStages, CurrentCachesAreReusedAndChangesRunTheStagesAgain) {
  Json json = tiny_solver_scene();
  simulate_scene(scene_of(json), options);
  testing::mark_files(out / "tiny/fluid");
  testing::mark_files(out / "tiny/diffuse");

  // Nothing changed: neither stage runs, no file is touched.
  SceneSimulation again = simulate_scene(scene_of(json), options);
  EXPECT_TRUE(again.fluid.reused);
  EXPECT_TRUE(again.diffuse.reused);
  EXPECT_EQ(testing::written_since_mark(out / "tiny/fluid"), std::vector<std::string>{});
  EXPECT_EQ(testing::written_since_mark(out / "tiny/diffuse"), std::vector<std::string>{});

  // A diffuse key: the fluid is reused, the diffuse stage runs.
  json["diffuse"] = {{"k_ta", 50}};
  again = simulate_scene(scene_of(json), options);
  EXPECT_TRUE(again.fluid.reused);
  EXPECT_FALSE(again.diffuse.reused);

  // A fluid key: both run (new fluid frames make the diffuse caches stale).
  json["fluid"]["solver"] = {{"viscosity", 0.002}};
  again = simulate_scene(scene_of(json), options);
  EXPECT_FALSE(again.fluid.reused);
  EXPECT_FALSE(again.diffuse.reused);

  // A missing frame file: the stage runs again.
  fs::remove(out / "tiny/fluid/fluid_0002.spf");
  again = simulate_scene(scene_of(json), options);
  EXPECT_FALSE(again.fluid.reused);
  EXPECT_TRUE(fs::is_regular_file(out / "tiny/fluid/fluid_0002.spf"));

  // More frames than cached: the fluid stage runs again to the new last frame; its first frames come
  // out byte for byte as before, so the diffuse stage continues from its last cached frame.
  json["fluid"]["frames"] = {0, 4};
  again = simulate_scene(scene_of(json), options);
  EXPECT_FALSE(again.fluid.reused);
  EXPECT_EQ(again.diffuse.continued_from, 3);
  EXPECT_EQ(again.diffuse.frames, 2);  // frame 3 again (not written), then frame 4
  EXPECT_TRUE(fs::is_regular_file(out / "tiny/diffuse/diffuse_0004.spd"));
  // The caches are quantized; the last frame's exact state is kept beside them to continue from, and
  // the one continued from is gone.
  EXPECT_TRUE(peek_diffuse_cache(out / "tiny/diffuse/diffuse_0004.spd").quantized);
  EXPECT_FALSE(peek_diffuse_cache(out / "tiny/diffuse/restart_0004.spd").quantized);
  EXPECT_FALSE(fs::exists(out / "tiny/diffuse/restart_0003.spd"));

  // Without that exact state the diffuse stage does not continue from the rounded cache: it starts over.
  fs::remove(out / "tiny/diffuse/restart_0004.spd");
  json["fluid"]["frames"] = {0, 5};
  again = simulate_scene(scene_of(json), options);
  EXPECT_EQ(again.diffuse.continued_from, -1);
  EXPECT_EQ(again.diffuse.frames, 6);
  EXPECT_TRUE(fs::is_regular_file(out / "tiny/diffuse/restart_0005.spd"));
}

// What farms ask before submitting a simulation job: would simulate_scene run anything?
TEST_F(PipelineStages, SimulationIsCurrentExactlyWhenSimulateSceneWouldRunNothing) {
  Json json = tiny_solver_scene();
  EXPECT_EQ(scene_frames(scene_of(json)), (std::vector<int>{0, 1, 2, 3}));  // known before any cache
  EXPECT_FALSE(scene_simulation_is_current(scene_of(json), options));       // nothing on disk
  simulate_scene(scene_of(json), options);
  EXPECT_TRUE(scene_simulation_is_current(scene_of(json), options));

  Json render_only = json;  // render keys are not the simulation's business
  render_only["render"] = {{"spp", 4}};
  const ParamReader root = ParamReader::from_json(render_only, "tiny.json");
  EXPECT_TRUE(scene_simulation_is_current(read_sim_scene(root, ".", "tiny"), options));

  json["diffuse"] = {{"k_ta", 50}};
  EXPECT_FALSE(scene_simulation_is_current(scene_of(json), options));  // a diffuse key changed
  simulate_scene(scene_of(json), options);
  EXPECT_TRUE(scene_simulation_is_current(scene_of(json), options));
  fs::remove(out / "tiny/fluid/fluid_0001.spf");
  EXPECT_FALSE(scene_simulation_is_current(scene_of(json), options));  // a fluid frame is missing
  simulate_scene(scene_of(json), options);
  fs::remove(out / "tiny/diffuse/diffuse_0003.spd");
  EXPECT_FALSE(scene_simulation_is_current(scene_of(json), options));  // a diffuse frame is missing
}

TEST_F(PipelineStages, SolverStatsAndTheLastLineGiveTheFastestParticle) {
  // No solids: the block falls freely, keeps its lattice (no compression, no pressure) and every
  // particle moves at g t, 0.4905 m/s a frame at 20 fps.
  Json json = tiny_solver_scene();
  json.erase("solids");
  FluidStageOptions fluid;
  fluid.out_root = out;
  fluid.quiet = false;
  ::testing::internal::CaptureStderr();
  run_fluid_stage(scene_of(json), fluid);
  const std::string log = ::testing::internal::GetCapturedStderr();
  const auto rows = testing::read_csv(out / "tiny/fluid/solver_stats.csv");
  ASSERT_EQ(rows.size(), 5u);
  ASSERT_EQ(rows[0].size(), 13u);
  EXPECT_EQ(rows[0][9], "max_speed");
  EXPECT_EQ(rows[0][10], "step_cap_ms");
  EXPECT_EQ(rows[0][11], "retries");
  for (int k = 0; k <= 3; ++k) {
    EXPECT_NEAR(std::stod(rows[k + 1][9]), 9.81 * k / 20.0, 1e-3) << "frame " << k;
    // 0.2 m deep at r = 2.5 cm: depth_cfl's 0.55 x 0.05 / sqrt(9.81 x 0.2) = 19.6 ms, so max_dt's 5 ms binds.
    EXPECT_EQ(rows[k + 1][10], "5.0000") << "frame " << k;
    EXPECT_EQ(rows[k + 1][11], "0") << "frame " << k;
  }
  // The stage's last line names the run's fastest particle: any particle of the last frame.
  const size_t at = log.rfind("fastest particle ");
  ASSERT_NE(at, std::string::npos) << log;
  const std::string said = log.substr(at + 17);
  EXPECT_NEAR(std::stod(said), 9.81 * 3 / 20.0, 1e-3) << said;
  EXPECT_NE(said.find(" m/s (frame 3) -> "), std::string::npos) << said;
}

TEST(SceneKeys, SameSettingsInAnyKeyOrderAgreeAndFrameRangeIsLeftOut) {
  Json a = tiny_solver_scene();
  Json b = Json::parse(R"({
    "solids": [{"max": [0.4, 0.6, 0.4], "min": [0, 0, 0], "type": "tank"}],
    "fluid": {"blocks": [{"max": [0.3, 0.3, 0.3], "min": [0.1, 0.1, 0.1]}], "frames": [0, 9],
              "fps": 20, "radius": 0.025, "source": "solver"},
    "name": "tiny"
  })");
  EXPECT_EQ(scene_of(a).fluid_keys, scene_of(b).fluid_keys);
  a["diffuse"] = {{"k_wc", 10}};
  EXPECT_EQ(scene_of(a).fluid_keys, scene_of(b).fluid_keys);
  EXPECT_NE(scene_of(a).diffuse_keys, scene_of(b).diffuse_keys);
  a["gravity"] = {0, -9.0, 0};
  EXPECT_NE(scene_of(a).fluid_keys, scene_of(b).fluid_keys);
}

}  // namespace
}  // namespace spume
