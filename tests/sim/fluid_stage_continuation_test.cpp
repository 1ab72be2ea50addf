// The fluid stage continues a cached prefix instead of solving again: frames 0-5 and then 0-10 leave
// the same bytes in the fluid folder as one run of 0-10 (frames, restart state, record; the stats
// rows but for their wall-clock column; the body track), with and without a moving solid, with
// dynamic bodies, and across thread counts. A folder whose restart state or body track is gone or
// does not agree is solved again from t = 0 and the stage says why.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unistd.h>

#include "sim/core/parallel.h"
#include "sim/stage/fluid_continuation.h"
#include "sim/stage/fluid_stage.h"
#include "tests/support/temp_dir.h"
#include "tests/support/written_files.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

// A 0.2 m cube of water (r = 0.02 m: 125 particles) dropped into a small tank, 20 fps; `extra`
// solids are added to the tank.
SimScene scene_with(const Json& extra = Json::array()) {
  Json json = Json::parse(R"({
    "name": "cont",
    "fluid": {"source": "solver", "radius": 0.02, "fps": 20, "frames": [0, 10],
              "blocks": [{"min": [0.1, 0.1, 0.05], "max": [0.3, 0.3, 0.25]}]},
    "solids": [{"type": "tank", "min": [0, 0, 0], "max": [0.5, 0.5, 0.3]}]
  })");
  for (const Json& s : extra) json["solids"].push_back(s);
  return read_sim_scene(ParamReader::from_json(json, "cont.json"), ".", "cont");
}

// A wall at the back of the tank oscillating into the fluid from t = 0.
const Json kPiston = Json::parse(R"([{"type": "box", "min": [0, 0, 0], "max": [0.06, 0.5, 0.3],
  "motion": {"type": "sine", "axis": [1, 0, 0], "amplitude": 0.04, "frequency": 2, "phase": 0.5}}])");
// A ball floating in from above and a dense flat box resting on the floor in the water's way.
const Json kBodies = Json::parse(R"([{"type": "sphere", "center": [0.4, 0.35, 0.15], "radius": 0.05,
  "dynamic": {"density": 500}}, {"type": "box", "min": [0.32, 0, 0.05], "max": [0.45, 0.03, 0.2],
  "dynamic": {"density": 3000}}])");

std::string file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// solver_stats.csv without its last column (wall-clock seconds).
std::string stats_without_seconds(const fs::path& p) {
  std::istringstream in(file_bytes(p));
  std::string line, out;
  while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

// Every file of the folder by name, with its bytes (stats without their seconds).
std::map<std::string, std::string> folder(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    files[name] = name == "solver_stats.csv" ? stats_without_seconds(e.path()) : file_bytes(e.path());
  }
  return files;
}

class FluidStageContinuation : public ::testing::Test {
 protected:
  void TearDown() override { set_thread_count(0); }
  FluidStageSummary run(const SimScene& scene, const std::string& out, int last, int threads, bool quiet = true) {
    set_thread_count(threads);
    FluidStageOptions o;
    o.out_root = root / out;
    o.quiet = quiet;
    o.last_frame = last;
    return run_fluid_stage(scene, o);
  }
  fs::path dir(const std::string& out) const { return root / out / "cont" / "fluid"; }

  // 0-5 then 0-10 against one 0-10 run: the same files, byte for byte.
  void expect_continued_like_one_run(const SimScene& scene) {
    const FluidStageSummary first = run(scene, "parts", 5, 1);
    EXPECT_EQ(first.frames, 6);
    EXPECT_EQ(first.continued_from, -1);
    EXPECT_TRUE(fs::is_regular_file(dir("parts") / "restart_0005.spr"));
    testing::mark_files(dir("parts"));

    const FluidStageSummary second = run(scene, "parts", 10, 2);
    EXPECT_FALSE(second.reused);
    EXPECT_EQ(second.continued_from, 5);
    EXPECT_EQ(second.frames, 5);  // 6..10
    const std::vector<std::string> written = testing::written_since_mark(dir("parts"));
    EXPECT_EQ(std::find(written.begin(), written.end(), "fluid_0003.spf"), written.end());  // earlier frames are not rewritten
    EXPECT_FALSE(fs::exists(dir("parts") / "restart_0005.spr"));  // only the last frame's state is kept

    run(scene, "whole", 10, 2);
    const auto parts = folder(dir("parts")), whole = folder(dir("whole"));
    // 11 frames, restart_0010.spr, solver_stats.csv, record.json, and bodies.csv with dynamic solids
    ASSERT_EQ(whole.size(), scene.solids.any_dynamic() ? 15u : 14u);
    EXPECT_TRUE(whole.count("restart_0010.spr"));
    for (const auto& [name, bytes] : whole) {
      ASSERT_TRUE(parts.count(name)) << name << " is missing from the continued run";
      EXPECT_TRUE(parts.at(name) == bytes) << name << " differs";
    }
    EXPECT_EQ(parts.size(), whole.size());
  }

  const testing::TempDir temp;
  const fs::path& root = temp.path;
};

TEST_F(FluidStageContinuation, ALongerRangeContinuesAndMatchesOneRunByteForByte) {
  expect_continued_like_one_run(scene_with());
}

TEST_F(FluidStageContinuation, WithAKinematicSolidTheContinuedRunMatchesToo) {
  expect_continued_like_one_run(scene_with(kPiston));
}

TEST_F(FluidStageContinuation, WithDynamicBodiesTheContinuedRunMatchesToo) {
  const SimScene scene = scene_with(kBodies);
  expect_continued_like_one_run(scene);
  // The bodies moved: the ball fell in and the flow pushed the box.
  const std::string track = file_bytes(dir("whole") / "bodies.csv");
  EXPECT_NE(track.find("\n10,"), std::string::npos) << track;
}

TEST_F(FluidStageContinuation, ABodyTrackThatDisagreesMeansSolvingAgainSayingWhy) {
  const SimScene scene = scene_with(kBodies);
  run(scene, "parts", 3, 1);
  // Frame 3's first body row with its x changed in the 9th digit.
  std::string track = file_bytes(dir("parts") / "bodies.csv");
  const size_t row = track.find("\n3,");
  ASSERT_NE(row, std::string::npos) << track;
  const size_t digit = track.find(',', track.find(',', row + 1) + 1) - 1;
  track[digit] = track[digit] == '1' ? '2' : '1';
  std::ofstream(dir("parts") / "bodies.csv", std::ios::binary | std::ios::trunc) << track;
  ::testing::internal::CaptureStderr();
  const FluidStageSummary again = run(scene, "parts", 6, 2, false);
  const std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(again.continued_from, -1);
  EXPECT_NE(said.find("re-solving from t = 0"), std::string::npos) << said;
  EXPECT_NE(said.find("bodies.csv"), std::string::npos) << said;
}

TEST_F(FluidStageContinuation, AMissingOrCorruptRestartStateMeansSolvingAgain) {
  const SimScene scene = scene_with();
  run(scene, "parts", 3, 1);
  fs::remove(dir("parts") / "restart_0003.spr");
  ::testing::internal::CaptureStderr();
  FluidStageSummary again = run(scene, "parts", 5, 1, false);
  std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(again.continued_from, -1);
  EXPECT_NE(said.find("restart_0003.spr is missing"), std::string::npos) << said;

  // Another frame's state under the last frame's name.
  fs::copy_file(dir("parts") / "restart_0005.spr", root / "saved.spr");
  EXPECT_EQ(run(scene, "parts", 6, 1).continued_from, 5);
  fs::remove(dir("parts") / "restart_0006.spr");
  fs::copy_file(root / "saved.spr", dir("parts") / "restart_0006.spr");
  ::testing::internal::CaptureStderr();
  again = run(scene, "parts", 7, 1, false);
  said = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(again.continued_from, -1);
  EXPECT_NE(said.find("made for frame 5"), std::string::npos) << said;

  // A last frame's cache that the state was not written with (here: the frame before it).
  fs::copy_file(dir("parts") / "fluid_0006.spf", dir("parts") / "fluid_0007.spf", fs::copy_options::overwrite_existing);
  ::testing::internal::CaptureStderr();
  again = run(scene, "parts", 8, 1, false);
  said = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(again.continued_from, -1);
  EXPECT_NE(said.find("does not hold the particles of"), std::string::npos) << said;

  // Corrupt bytes: the CRC says so.
  {
    std::fstream f(dir("parts") / "restart_0008.spr", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(300);
    f.put('\x7f');
  }
  ::testing::internal::CaptureStderr();
  again = run(scene, "parts", 9, 1, false);
  said = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(again.continued_from, -1);
  EXPECT_NE(said.find("CRC-32 mismatch"), std::string::npos) << said;

  // The re-solved folder continues again.
  again = run(scene, "parts", 10, 1);
  EXPECT_EQ(again.continued_from, 9);
}

}  // namespace
}  // namespace spume
