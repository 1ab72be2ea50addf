// A moving cache from "another simulator", as a user brings it: spume's own dam break exported as
// BGEO and post-processed with --fluid alone (no tank), with the tank given, and with the tank
// inferred (asked for, and by default).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/csv.h"
#include "tests/support/files.h"
#include "tests/support/run_spume.h"
#include "tests/support/text.h"
#include "tests/support/temp_dir.h"
#include "sim/io/spume_cache.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

using testing::CommandResult;
using testing::contains;
using testing::run_spume;

// Sums of two columns of stats.csv (generated, removed) over every frame.
std::pair<long, long> emitted_and_removed(const fs::path& stats) {
  const auto rows = testing::read_csv(stats);
  return {long(testing::column_sum(rows, "generated")), long(testing::column_sum(rows, "removed"))};
}

// A 1 m water column at one end of a 4 m tank (r = 0.04 m: 720 particles), 1.6 s at 25 fps: the
// front reaches the far wall after about 0.8 s and climbs it.
constexpr const char* kTank = R"({"type": "tank", "min": [0, 0, 0], "max": [4, 1.5, 0.4]})";

class RealCache : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    temp = std::make_unique<testing::TempDir>("RealCache");
    dir = temp->path;
    std::ofstream(dir / "dam.json") << R"({
      "name": "dam",
      "fluid": {"source": "solver", "radius": 0.04, "fps": 25, "frames": [0, 40],
                "blocks": [{"min": [0, 0, 0], "max": [1, 1, 0.4]}]},
      "solids": [)" << kTank << R"(],
      "output": {"fluid_bgeo": true}
    })";
    solved = run_spume("simulate " + (dir / "dam.json").string() + " --out " + (dir / "out").string());
  }
  static void TearDownTestSuite() { temp.reset(); }
  static std::string bgeo_pattern() { return (dir / "out/dam/fluid_bgeo/fluid_%04d.bgeo").string(); }

  static std::unique_ptr<testing::TempDir> temp;
  static fs::path dir;
  static CommandResult solved;
};

std::unique_ptr<testing::TempDir> RealCache::temp;
fs::path RealCache::dir;
CommandResult RealCache::solved;

TEST_F(RealCache, TheMovingCacheAloneKeepsWhatItEmits) {
  ASSERT_EQ(solved.status, 0) << solved.output;
  const CommandResult r = run_spume("simulate --fluid '" + bgeo_pattern() + "' --radius 0.04 --fps 25 --tank none --out " +
                                    (dir / "alone").string());
  ASSERT_EQ(r.status, 0) << r.output;
  // The domain holds every frame's fluid, not the first frame's.
  EXPECT_NE(r.output.find("the fluid's bounds over all 41 frames"), std::string::npos) << r.output;
  const auto [emitted, removed] = emitted_and_removed(dir / "alone/fluid/stats.csv");
  EXPECT_GT(emitted, 1000);
  EXPECT_LT(removed * 100, emitted) << removed << " of " << emitted;
}

// A domain lower than the splash loses diffuse particles, and the warning's advice depends on what holds
// them: with the tank, widen the domain; with no container (--tank none), spray falls through where the
// floor is, so the container is named first.
TEST_F(RealCache, ADomainThatLosesParticlesIsAdvisedOnWhatHoldsThem) {
  ASSERT_EQ(solved.status, 0) << solved.output;
  const std::string low = " --set 'domain.min=[-1, -1, -1]' --set 'domain.max=[5, 0.3, 1.4]'";
  for (const bool tank : {true, false}) {
    SCOPED_TRACE(tank ? "the tank given" : "--tank none");
    const CommandResult r = run_spume("simulate --fluid '" + bgeo_pattern() + "' --radius 0.04 --fps 25" +
                                      std::string(tank ? " --tank 0,0,0,4,1.5,0.4" : " --tank none") + low + " --out " +
                                      (dir / (tank ? "low_tank" : "low_none")).string());
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_TRUE(contains(r.output, "diffuse particles outside the domain")) << r.output;
    EXPECT_EQ(contains(r.output, "the run has no container"), !tank) << r.output;
    EXPECT_EQ(contains(r.output, "emitted; if the flow reaches beyond the domain, widen"), tank) << r.output;
  }
}

TEST_F(RealCache, WithTheTankGivenItMatchesTheSolverScenesDiffuseStage) {
  ASSERT_EQ(solved.status, 0) << solved.output;
  std::ofstream(dir / "post.json") << R"({"name": "post", "fluid": {"files": ")" << bgeo_pattern()
                                   << R"(", "radius": 0.04, "fps": 25}, "solids": [)" << kTank << "]}";
  const CommandResult r = run_spume("simulate " + (dir / "post.json").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  int compared = 0;
  for (int k = 0; k <= 40; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "diffuse/diffuse_%04d.spd", k);
    const std::string a = testing::read_file(dir / "out/dam" / name), b = testing::read_file(dir / "out/post" / name);
    ASSERT_FALSE(a.empty()) << name;
    EXPECT_TRUE(a == b) << name << " differs";
    compared += peek_diffuse_cache(dir / "out/dam" / name).count > 0;
  }
  EXPECT_GT(compared, 20);  // most frames hold diffuse particles
}

// Walls at x = 0 and 4, y = 0, z = 0 and 0.4, each found within one particle radius.
void expect_the_tanks_walls(const std::string& output) {
  const size_t at_line = output.find("container inferred from the fluid: walls ");
  ASSERT_NE(at_line, std::string::npos) << output;
  const std::string line = output.substr(at_line, output.find('\n', at_line) - at_line);
  auto wall = [&](const std::string& side) {
    const size_t at = line.find(side + " at ");
    EXPECT_NE(at, std::string::npos) << side << ": " << line;
    return at == std::string::npos ? 1e9 : std::stod(line.substr(at + side.size() + 4));
  };
  EXPECT_NEAR(wall("-x"), 0.0, 0.04);
  EXPECT_NEAR(wall("+x"), 4.0, 0.04);
  EXPECT_NEAR(wall("-y"), 0.0, 0.04);
  EXPECT_NEAR(wall("-z"), 0.0, 0.04);
  EXPECT_NEAR(wall("+z"), 0.4, 0.04);
  EXPECT_EQ(line.find("open: "), std::string::npos) << line;  // the top only
}

TEST_F(RealCache, TheTankIsInferredFromTheFluid) {
  ASSERT_EQ(solved.status, 0) << solved.output;
  const CommandResult r = run_spume("simulate --fluid '" + bgeo_pattern() + "' --radius 0.04 --fps 25 --tank auto --out " +
                                    (dir / "inferred").string());
  ASSERT_EQ(r.status, 0) << r.output;
  expect_the_tanks_walls(r.output);
  const auto [emitted, removed] = emitted_and_removed(dir / "inferred/fluid/stats.csv");
  EXPECT_EQ(removed, 0) << "of " << emitted;
}

// Without --tank, the one-line run uses the tank the fluid shows, and says so.
TEST_F(RealCache, TheOneLineRunUsesTheInferredTankByDefault) {
  ASSERT_EQ(solved.status, 0) << solved.output;
  const CommandResult r = run_spume("simulate --fluid '" + bgeo_pattern() + "' --radius 0.04 --fps 25 --out " +
                                    (dir / "default").string());
  ASSERT_EQ(r.status, 0) << r.output;
  expect_the_tanks_walls(r.output);
  EXPECT_NE(r.output.find("used since no --tank was given (--tank none runs without it)"), std::string::npos) << r.output;
  const auto [emitted, removed] = emitted_and_removed(dir / "default/fluid/stats.csv");
  EXPECT_EQ(removed, 0) << "of " << emitted;
}

}  // namespace
}  // namespace spume
