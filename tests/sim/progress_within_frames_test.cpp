// Progress inside long frames (core/progress.h): lines within an item are throttled (here stderr is
// not a terminal, so at most one per 10 s by default), say which item is under way and how far, and
// never appear when quiet. The fluid stage reports its steps and simulated time within each frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "sim/core/progress.h"
#include "sim/stage/fluid_stage.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

std::string stderr_of(const std::function<void()>& fn) {
  ::testing::internal::CaptureStderr();
  fn();
  return ::testing::internal::GetCapturedStderr();
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(ProgressWithinFrames, PartialLinesNameTheItemUnderWayAndAreThrottled) {
  ASSERT_EQ(::isatty(2), 0) << "these expectations are for a log, not a terminal";
  EXPECT_EQ(stderr_of([] {
              Progress p("fluid x", 10, false, 0.0);
              p.partial(2, "frame 2: 40 steps");
            }),
            "fluid x: frame 3/10 in progress  frame 2: 40 steps\n");

  // Off a terminal the default is 10 s since the last line: nothing yet, however often it is asked.
  // Per-item lines are not throttled.
  const std::vector<std::string> lines = lines_of(stderr_of([] {
    Progress p("fluid x", 10, false);
    EXPECT_FALSE(p.partial_due());
    for (int k = 0; k < 1000; ++k) p.partial(0, "frame 0");
    p.update(1, "done");
    p.partial(1, "frame 1");
  }));
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].rfind("fluid x: frame 1/10  ", 0), 0u) << lines[0];

  EXPECT_EQ(stderr_of([] {
              Progress p("fluid x", 10, true, 0.0);
              EXPECT_FALSE(p.partial_due());
              p.partial(2, "frame 2");
            }),
            "");
}

// The tiny falling cube of stages_test.cpp, frames 0-3 at 20 fps (about 10 steps a frame).
SimScene tiny() {
  const Json json = Json::parse(R"({
    "name": "tiny",
    "fluid": {"source": "solver", "radius": 0.025, "fps": 20, "frames": [0, 3],
              "blocks": [{"min": [0.1, 0.1, 0.1], "max": [0.3, 0.3, 0.3]}]},
    "solids": [{"type": "tank", "min": [0, 0, 0], "max": [0.4, 0.6, 0.4]}]
  })");
  return read_sim_scene(ParamReader::from_json(json, "tiny.json"), ".", "tiny");
}

TEST(ProgressWithinFrames, FluidStageReportsStepsAndTimeWithinEachFrameUnlessQuiet) {
  const testing::TempDir temp;
  const std::filesystem::path& out = temp.path;
  FluidStageOptions o;
  o.out_root = out;
  o.partial_progress_interval = 0.0;  // every step
  const std::string said = stderr_of([&] { run_fluid_stage(tiny(), o); });
  const std::regex partial(R"(fluid tiny: frame (\d)/4 in progress  frame (\d): (\d+) steps, t = ([0-9.e-]+) of ([0-9.e-]+) s)");
  int count = 0, last_steps = 0, last_frame = -1;
  for (const std::string& line : lines_of(said)) {
    std::smatch m;
    if (!std::regex_match(line, m, partial)) continue;
    ++count;
    const int item = std::stoi(m[1]), frame = std::stoi(m[2]), steps = std::stoi(m[3]);
    EXPECT_EQ(item, frame + 1) << line;  // frames 0-3 are items 1-4
    EXPECT_GE(frame, 1) << line;         // frame 0 takes no step
    if (frame == last_frame) EXPECT_EQ(steps, last_steps + 1) << line;
    else EXPECT_EQ(steps, 1) << line;
    const double t = std::stod(m[4]), end = std::stod(m[5]);
    EXPECT_DOUBLE_EQ(end, frame / 20.0) << line;
    EXPECT_GT(t, (frame - 1) / 20.0) << line;
    EXPECT_LE(t, end) << line;
    last_frame = frame, last_steps = steps;
  }
  EXPECT_GE(count, 3 * 5) << said;  // every step of frames 1-3

  fs::remove_all(out);
  o.quiet = true;
  EXPECT_EQ(stderr_of([&] { run_fluid_stage(tiny(), o); }), "");
}

}  // namespace
}  // namespace spume
