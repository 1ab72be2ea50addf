// Never a stale, mixed or silently wrong frame, through the spume binary: changed inputs,
// keys and caches are noticed; frames know their sources; one writer per output folder; what killed
// runs leave is cleared; gaps are errors; nonsense is refused.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "sim/core/output_lock.h"
#include "render/image/png_io.h"
#include "sim/io/bgeo.h"
#include "sim/io/stage_record.h"
#include "tests/support/files.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_fluids.h"
#include "tests/support/written_files.h"
#include "tests/support/text.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

using testing::CommandResult;
using testing::run_spume;

using spume::testing::contains;

// Eight BGEO frames (numbered 1-8, 50 fps) of two blocks of water thrown at each other in a tank, and
// a scene that draws the surface and the diffuse material at 64x36.
class Provenance : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir / "cache");
    for (int k = 1; k <= 8; ++k) write_frame(k, 2.0f);
    std::ofstream(dir / "scene.json") << R"({
      "name": "blocks",
      "fluid": {"files": "cache/fluid_%d.bgeo", "radius": 0.02},
      "solids": [{"type": "tank", "min": [-0.1, -0.02, -0.1], "max": [0.6, 0.6, 0.3]}],
      "diffuse": {"k_ta": 2000, "k_wc": 2000},
      "render": {"resolution": [64, 36], "camera": {"position": [0.25, 0.5, 1.2], "target": [0.25, 0.1, 0.1]}}
    })";
  }

  // Frame k: the blocks 0.04 m closer at each frame, moving at `speed` m/s.
  void write_frame(int k, float speed) {
    write_bgeo(frame_file(k), testing::blocks_closing_in(k, 0.16f, 0.5f, Vec3f(speed, 1, 0)));
  }
  fs::path frame_file(int k) const { return dir / "cache" / ("fluid_" + std::to_string(k) + ".bgeo"); }
  std::string args(const std::string& more = "") const {
    return (dir / "scene.json").string() + " --out " + (dir / "out").string() + " " + more;
  }
  fs::path out(const std::string& relative) const { return dir / "out/blocks" / relative; }
  fs::path png(int k) const {
    char name[32];
    std::snprintf(name, sizeof name, "frames/%04d.png", k);
    return out(name);
  }

  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

TEST_F(Provenance, ReExportedInputFilesAreSimulatedAndRenderedAgain) {
  CommandResult r = run_spume("run " + args());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "8 frames written")) << r.output;
  testing::mark_files(out("diffuse"));
  const std::string record = testing::read_file(out("diffuse/record.json"));
  r = run_spume("run " + args());
  ASSERT_EQ(r.status, 0) << r.output;
  // The diffuse stage was skipped: not one of its files was written again.
  EXPECT_EQ(testing::written_since_mark(out("diffuse")), std::vector<std::string>{});
  EXPECT_EQ(testing::read_file(out("diffuse/record.json")), record);
  EXPECT_TRUE(contains(r.output, "0 frames written, 8 current on disk")) << r.output;

  // Frames 5-8 re-exported (faster flow), same names, a second later than the first export (set
  // explicitly: a rewrite within the clock's resolution could keep the time): the diffuse stage runs
  // again and says why, and the frames are drawn again.
  for (int k = 5; k <= 8; ++k) {
    const fs::file_time_type exported = fs::last_write_time(frame_file(k));
    write_frame(k, 3.0f);
    fs::last_write_time(frame_file(k), exported + std::chrono::seconds(1));
  }
  r = run_spume("run " + args());
  ASSERT_EQ(r.status, 0) << r.output;
  // The diffuse stage ran: its record was written again and names the re-exported files.
  const std::vector<std::string> rewritten = testing::written_since_mark(out("diffuse"));
  EXPECT_NE(std::find(rewritten.begin(), rewritten.end(), "record.json"), rewritten.end());
  const std::optional<StageRecord> made = read_stage_record(out("diffuse"));
  ASSERT_TRUE(made);
  for (int k = 5; k <= 8; ++k) EXPECT_EQ(made->frame_inputs.at(k), file_identity(frame_file(k))) << k;
  EXPECT_TRUE(contains(r.output, "the input file of frame 5 changed")) << r.output;
  EXPECT_FALSE(contains(r.output, "0 frames written")) << r.output;
}

TEST_F(Provenance, RenderRefusesCachesMadeWithOtherKeysOrUnfinished) {
  ASSERT_EQ(run_spume("simulate " + args()).status, 0);
  CommandResult r = run_spume("render " + args("--set diffuse.drag=0.9"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "diffuse.drag: 0.5 -> 0.9")) << r.output;  // the default drag, as used
  EXPECT_TRUE(contains(r.output, "spume simulate")) << r.output;
  EXPECT_FALSE(fs::exists(png(1)));

  // A simulation with new keys, then a render with the same keys draws every frame from them.
  ASSERT_EQ(run_spume("render " + args()).status, 0);
  ASSERT_EQ(run_spume("simulate " + args("--set diffuse.seed=2")).status, 0);
  r = run_spume("render " + args("--set diffuse.seed=2"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "8 frames written")) << r.output;
  // ... and the old keys no longer match the caches.
  r = run_spume("render " + args());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "diffuse.seed: 2 -> 1")) << r.output;  // back to the default seed

  // A simulation that was killed leaves no record: its caches are refused as unfinished.
  fs::remove(out("diffuse/record.json"));
  r = run_spume("render " + args("--set diffuse.seed=2"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "no finished diffuse caches")) << r.output;
}

TEST_F(Provenance, RerenderingSomeFramesWithNewKeysKeepsTheOthers) {
  ASSERT_EQ(run_spume("run " + args()).status, 0);
  const std::string first_record = *read_png_record(png(5));
  CommandResult r = run_spume("render " + args("--frames 5 --set render.alpha=60"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "1 frames written")) << r.output;
  EXPECT_TRUE(contains(r.output, "7 other frames on disk are stale")) << r.output;
  for (int k = 1; k <= 8; ++k) EXPECT_TRUE(fs::exists(png(k))) << k;
  EXPECT_NE(*read_png_record(png(5)), first_record);
  EXPECT_TRUE(contains(*read_png_record(png(5)), "\"alpha\":60"));
  // Back to the scene's keys: only frame 5 is drawn again.
  r = run_spume("render " + args());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "1 frames written, 7 current on disk")) << r.output;
  EXPECT_EQ(*read_png_record(png(5)), first_record);
}

TEST_F(Provenance, ASecondWriterWaitsForTheFolder) {
  ASSERT_EQ(run_spume("simulate " + args()).status, 0);
  // This process holds the folder as a simulation would; a render started now must wait for it.
  auto held = std::make_unique<OutputLock>(dir / "out/blocks", OutputLock::Mode::Exclusive, "", "the test", true);
  const fs::path log = dir / "render.log";
  const std::string command = std::string(SPUME_BINARY) + " render " + args() + " > " + log.string() + " 2>&1";
  std::thread render([&] { std::system(command.c_str()); });
  // Until the render says it waits (at most a minute, on a busy machine), and 1.5 s more.
  const auto start = std::chrono::steady_clock::now();
  while (!contains(testing::read_file(log), "waiting for the test") &&
         std::chrono::steady_clock::now() - start < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_FALSE(fs::exists(png(1)));  // still waiting
  held.reset();
  render.join();
  const std::string output = testing::read_file(log);
  EXPECT_TRUE(contains(output, "waiting for the test")) << output;
  EXPECT_TRUE(contains(output, "8 frames written")) << output;
}

TEST_F(Provenance, TemporariesOfKilledWritersAreRemoved) {
  ASSERT_EQ(run_spume("simulate " + args()).status, 0);
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ::waitpid(dead, nullptr, 0);
  const fs::path killed = out("diffuse/diffuse_0004.spd.tmp." + std::string(host) + "." + std::to_string(dead));
  const fs::path alive = out("diffuse/diffuse_0005.spd.tmp." + std::string(host) + "." + std::to_string(::getpid()));
  const fs::path elsewhere = out("diffuse/diffuse_0006.spd.tmp.another-host." + std::to_string(dead));
  for (const fs::path& p : {killed, alive, elsewhere}) std::ofstream(p) << "half a cache";
  const CommandResult r = run_spume("simulate " + args());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(killed));
  EXPECT_TRUE(fs::exists(alive));      // its writer still runs
  EXPECT_TRUE(fs::exists(elsewhere));  // another host's process: not ours to judge
  EXPECT_TRUE(contains(r.output, "removed 1 temporary files")) << r.output;
}

TEST_F(Provenance, AMissingInputFrameIsAnErrorUnlessGapsAreAllowed) {
  fs::remove(frame_file(3));
  CommandResult r = run_spume("simulate " + args());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "fluid frame 3 is missing")) << r.output;
  EXPECT_TRUE(contains(r.output, "allow_gaps")) << r.output;
  EXPECT_FALSE(fs::exists(out("diffuse/record.json")));

  r = run_spume("run " + args("--allow-gaps"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "interpolated")) << r.output;
  EXPECT_TRUE(fs::exists(out("diffuse/diffuse_0003.spd")));
  EXPECT_TRUE(fs::exists(png(3)));
}

TEST_F(Provenance, NonsenseIsRefusedOrWarnedAbout) {
  CommandResult r = run_spume("simulate " + args("--set diffuse.k_ta=1e39"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "/diffuse/k_ta: value 1e+39 is too large")) << r.output;
  r = run_spume("simulate " + args("--set diffuse.tau_ta=[1,1.00000001]"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "must be below max")) << r.output;
  // A radius 250 times the particles' spacing: warned, with both numbers.
  r = run_spume("simulate " + args("--set fluid.radius=5"));
  EXPECT_TRUE(contains(r.output, "warning: fluid.radius 5 m implies a particle spacing of 10 m")) << r.output;
  EXPECT_TRUE(contains(r.output, "0.04 m from their nearest neighbour")) << r.output;
}

TEST_F(Provenance, ATopDownCameraDrawsAPicture) {
  const CommandResult r = run_spume(
      "run " + args("--frames 6 --set render.camera.position=[0.25,2,0.1] --set render.camera.target=[0.25,0,0.1]"));
  ASSERT_EQ(r.status, 0) << r.output;
  const ImageRGB8 image = read_png(png(6));
  int distinct = 0;
  for (size_t i = 3; i < image.rgb.size(); i += 3) distinct += image.rgb[i] != image.rgb[0];
  EXPECT_GT(distinct, 100);  // not a blank frame
}

TEST_F(Provenance, RunSimulatesOnlyAsFarAsTheFramesAskedFor) {
  CommandResult r = run_spume("run " + args("--frames 1-3"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(out("diffuse/diffuse_0003.spd")));
  EXPECT_FALSE(fs::exists(out("diffuse/diffuse_0004.spd")));
  r = run_spume("run " + args());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "continuing from frame 3")) << r.output;
  // Continuing gives the same caches as one run from the start.
  const fs::path straight = dir / "straight";
  ASSERT_EQ(run_spume("simulate " + (dir / "scene.json").string() + " --out " + straight.string()).status, 0);
  for (int k = 1; k <= 8; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "diffuse/diffuse_%04d.spd", k);
    std::ifstream a(out(name), std::ios::binary), b(straight / "blocks" / name, std::ios::binary);
    const std::string x((std::istreambuf_iterator<char>(a)), {}), y((std::istreambuf_iterator<char>(b)), {});
    EXPECT_TRUE(x == y) << name;
  }
}

// With two threads the next frame loads while one renders, each PNG is written while the next frame
// renders, and the volume pass runs beside the surface pass; with one, each in turn. The frames, their
// order on stdout and their rows of render_stats.csv are the same.
TEST_F(Provenance, FramesAreTheSameBytesDrawnInTurnOrSideBySide) {
  ASSERT_EQ(run_spume("simulate " + args()).status, 0);
  std::vector<std::string> in_turn;
  for (const char* threads : {"1", "2"}) {
    const CommandResult r = run_spume("render " + args(std::string("--overwrite --threads ") + threads));
    ASSERT_EQ(r.status, 0) << r.output;
    size_t at = 0;
    for (int k = 1; k <= 8; ++k) {
      const size_t saved = r.output.find("Saved: " + png(k).string(), at);
      ASSERT_NE(saved, std::string::npos) << threads << " threads, frame " << k << ":\n" << r.output;
      at = saved + 1;
      const std::string bytes = testing::read_file(png(k));
      if (in_turn.size() < 8)
        in_turn.push_back(bytes);
      else
        EXPECT_TRUE(bytes == in_turn[size_t(k - 1)]) << "frame " << k;
    }
    const std::string stats = testing::read_file(out("render_stats.csv"));
    for (int k = 1; k <= 8; ++k) EXPECT_TRUE(contains(stats, "\n" + std::to_string(k) + ",")) << stats;
  }
}

}  // namespace
}  // namespace spume
