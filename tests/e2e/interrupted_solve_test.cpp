// A solver run killed midway (SIGKILL, no chance to clean up) continues from the last state it saved
// (sim/stage/fluid_stage.cpp saves one whenever the time since the last is 50 times what that took),
// and ends with the same fluid caches and body track, byte for byte, as one uninterrupted run.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "sim/io/stage_record.h"
#include "tests/support/files.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::contains;
using testing::read_file;
using testing::run_spume;

TEST(InterruptedSolve, AKilledRunContinuesFromItsLastSaveAndEndsAsOneRun) {
  testing::TempDir dir;
  // 1000 particles and two bodies (a ball falling in, a dense flat box on the floor), 100 frames.
  std::ofstream(dir / "scene.json") << R"({
    "name": "killed",
    "fluid": {"source": "solver", "radius": 0.01, "fps": 50, "frames": [0, 100],
              "blocks": [{"min": [0.05, 0, 0.05], "max": [0.25, 0.2, 0.25]}]},
    "solids": [{"type": "tank", "min": [0, 0, 0], "max": [0.5, 0.5, 0.3]},
               {"type": "sphere", "center": [0.4, 0.35, 0.15], "radius": 0.05, "dynamic": {"density": 500}},
               {"type": "box", "min": [0.32, 0, 0.05], "max": [0.45, 0.03, 0.2], "dynamic": {"density": 3000}}],
    "diffuse": {"k_ta": 100, "k_wc": 100}
  })";
  const fs::path fluid = dir / "a/killed/fluid";
  const std::string scene = (dir / "scene.json").string();

  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    ::execl(SPUME_BINARY, SPUME_BINARY, "simulate", scene.c_str(), "--out", (dir / "a").c_str(), (char*)nullptr);
    ::_exit(127);
  }
  // Killed once it has saved and solved on past frame 40.
  bool exited = false;
  for (int k = 0; k < 6000 && !(fs::exists(fluid / "record.json") && fs::exists(fluid / "fluid_0040.spf")); ++k) {
    int status = 0;
    if (::waitpid(child, &status, WNOHANG) == child) {
      exited = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_FALSE(exited) << "the run ended before it could be killed: make the scene longer";
  ::kill(child, SIGKILL);
  ::waitpid(child, nullptr, 0);
  const std::optional<StageRecord> saved = read_stage_record(fluid);
  ASSERT_TRUE(saved.has_value());
  ASSERT_GE(saved->last_frame, 1);
  ASSERT_LT(saved->last_frame, 100);

  const CommandResult again = run_spume("simulate " + scene + " --out " + (dir / "a").string());
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_TRUE(contains(again.output, "fluid: continuing from frame " + std::to_string(saved->last_frame)))
      << again.output;

  const CommandResult straight = run_spume("simulate " + scene + " --out " + (dir / "b").string() + " --quiet");
  ASSERT_EQ(straight.status, 0) << straight.output;
  char name[32];
  for (int f = 0; f <= 100; ++f) {
    std::snprintf(name, sizeof name, "fluid_%04d.spf", f);
    ASSERT_TRUE(fs::exists(fluid / name)) << name;
    EXPECT_TRUE(read_file(fluid / name) == read_file(dir / "b/killed/fluid" / name)) << name << " differs";
  }
  EXPECT_TRUE(read_file(fluid / "bodies.csv") == read_file(dir / "b/killed/fluid/bodies.csv"));
  EXPECT_TRUE(read_file(fluid / "restart_0100.spr") == read_file(dir / "b/killed/fluid/restart_0100.spr"));
}

}  // namespace
}  // namespace spume
