// Unreasonable input at the command line: the spume binary refuses it with exit status 1 and a
// message naming the key or file, the value and what is allowed, and writes nothing; where input is
// legal but binds a limit (the emission budget) it runs and warns.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "tests/stability/bad_files.h"
#include "sim/io/bgeo.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

using testing::run_spume;
using Result = testing::CommandResult;  // output: stdout and stderr

class StabilityCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir / "cache");
    // Four frames of two blocks running into each other at 2 m/s each.
    for (int k = 0; k < 4; ++k) {
      frames.push_back(testing::blocks_closing_in(k, 0.2f, 0.3f, Vec3f(2, 0, 0)));
      write_frame(k);
    }
  }

  void write_frame(int k) { write_bgeo(dir / "cache" / ("f_" + std::to_string(k) + ".bgeo"), frames[k]); }
  Result simulate(const std::string& diffuse) {
    std::ofstream(dir / "scene.json") << R"({"fluid": {"files": "cache/f_%d.bgeo", "radius": 0.02}, "diffuse": )"
                                      << diffuse << "}";
    return run_spume("simulate " + (dir / "scene.json").string() + " --out " + (dir / "out").string());
  }
  bool wrote_caches() const { return fs::exists(dir / "out" / "scene" / "diffuse" / "diffuse_0000.spd"); }

  const testing::TempDir temp;
  const fs::path& dir = temp.path;
  std::vector<FluidFrame> frames;
};

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST_F(StabilityCommand, PaperDragAboveOneIsRefused) {
  const Result r = simulate(R"({"bubble_drag": "paper", "drag": 1.5})");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(has(r.output, "/diffuse/drag")) << r.output;
  EXPECT_TRUE(has(r.output, "1.5")) << r.output;
  EXPECT_TRUE(has(r.output, "allowed [0, 1]")) << r.output;
  EXPECT_FALSE(wrote_caches());
}

TEST_F(StabilityCommand, ExponentialDragOfAMillionRuns) {
  const Result r = simulate(R"({"bubble_drag": "exponential", "drag": 1e6})");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(wrote_caches());
}

TEST_F(StabilityCommand, CrossedThresholdsAreRefused) {
  for (const char* keys : {R"({"tau_wc": [5, 2]})", R"({"tau_ta": [3, 3]})"}) {
    const Result r = simulate(keys);
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_TRUE(has(r.output, "must be below max")) << r.output;
    EXPECT_TRUE(has(r.output, "scene.json")) << r.output;
    EXPECT_FALSE(wrote_caches());
  }
}

TEST_F(StabilityCommand, NanInAFrameIsRefusedNamingFileAndParticle) {
  frames[2].positions[7].x() = stability::kMarker;
  write_frame(2);
  stability::spoil_marker(dir / "cache" / "f_2.bgeo", NAN, /*big_endian=*/true, /*crc_trailer=*/false);
  const Result r = simulate("{}");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(has(r.output, "f_2.bgeo")) << r.output;
  EXPECT_TRUE(has(r.output, "particle 7")) << r.output;
}

TEST_F(StabilityCommand, ABindingBudgetWarns) {
  const Result r = simulate(R"({"k_ta": 1e6, "k_wc": 1e6, "max_particles": 200})");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(has(r.output, "warning")) << r.output;
  EXPECT_TRUE(has(r.output, "max_particles = 200")) << r.output;
  // stats.csv: never more than 200 alive (spray + foam + bubbles, columns 4-6).
  std::ifstream stats(dir / "out" / "scene" / "stats.csv");
  std::string line;
  std::getline(stats, line);
  int rows = 0;
  while (std::getline(stats, line)) {
    std::stringstream row(line);
    std::string cell;
    std::vector<double> cells;
    while (std::getline(row, cell, ',')) cells.push_back(std::stod(cell));
    ASSERT_GE(cells.size(), 6u);
    EXPECT_LE(cells[3] + cells[4] + cells[5], 200.0) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 4);
}

}  // namespace
}  // namespace spume
