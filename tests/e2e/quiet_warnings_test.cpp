// --quiet hides progress and notes, never warnings: on every command a warning reaches stderr under
// --quiet in the words it has without it, once, and the warnings given while caches were made are kept
// in their records, said again when the caches are reused, and counted by `spume info OUT/<scene>`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sim/io/bgeo.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_fluids.h"
#include "tests/support/text.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

using testing::CommandResult;
using testing::contains;
using testing::run_spume;
using testing::SpumeOptions;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> warning_lines(const std::string& text) {
  std::vector<std::string> found;
  for (const std::string& line : lines_of(text))
    if (line.rfind("warning: ", 0) == 0) found.push_back(line);
  return found;
}

// Four BGEO frames of two blocks of water on a 0.04 m lattice thrown at each other in a tank. The
// scene's radius, 0.035 m, implies a spacing of 0.07 m, 1.75 times the particles' (the inputs warn),
// and an emission budget of 5 particles binds as soon as anything is emitted (the diffuse stage warns).
class QuietWarnings : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir / "cache");
    for (int k = 1; k <= 4; ++k)
      write_bgeo(dir / "cache" / ("fluid_" + std::to_string(k) + ".bgeo"),
                 testing::blocks_closing_in(k, 0.16f, 0.5f, Vec3f(2, 1, 0)));
    std::ofstream(dir / "scene.json") << R"({
      "name": "blocks",
      "fluid": {"files": "cache/fluid_%d.bgeo", "radius": 0.035},
      "solids": [{"type": "tank", "min": [-0.1, -0.02, -0.1], "max": [0.6, 0.6, 0.3]}],
      "diffuse": {"k_ta": 2000, "k_wc": 2000, "max_particles": 5},
      "render": {"resolution": [64, 36], "camera": {"position": [0.25, 0.5, 1.2], "target": [0.25, 0.1, 0.1]}}
    })";
  }

  std::string args(const std::string& more = "") const {
    return (dir / "scene.json").string() + " --out " + (dir / "out").string() + " " + more;
  }
  CommandResult spume(const std::string& arguments) const {
    return run_spume(arguments, SpumeOptions::stderr_apart());
  }

  const testing::TempDir temp;
  const fs::path& dir = temp.path;
  const std::string radius_warning = "warning: fluid.radius 0.035 m implies a particle spacing of 0.07 m";
  const std::string budget_warning = "warning: the emission budget diffuse.max_particles = 5 binds from frame";
};

bool starts_with_any(const std::vector<std::string>& lines, const std::string& prefix) {
  for (const std::string& line : lines)
    if (line.rfind(prefix, 0) == 0) return true;
  return false;
}

// Under --quiet, stderr holds the warnings and nothing else, in the words and order of a loud run.
TEST_F(QuietWarnings, SimulateKeepsItsWarningsAndDropsProgressAndNotes) {
  const CommandResult loud = spume("simulate " + args());
  ASSERT_EQ(loud.status, 0) << loud.err;
  const std::vector<std::string> said = warning_lines(loud.err);
  EXPECT_TRUE(starts_with_any(said, radius_warning)) << loud.err;
  EXPECT_TRUE(starts_with_any(said, budget_warning)) << loud.err;
  EXPECT_TRUE(contains(loud.err, "simulate blocks: frame 4/4")) << loud.err;  // progress, loud
  EXPECT_TRUE(contains(loud.err, "domain (diffuse particles leaving it are deleted)")) << loud.err;  // a note

  fs::remove_all(dir / "out");
  const CommandResult quiet = spume("simulate " + args("--quiet"));
  ASSERT_EQ(quiet.status, 0) << quiet.err;
  EXPECT_EQ(lines_of(quiet.err), said) << quiet.err;  // warnings only, once each, in the same words

  // Kept with the caches: the record holds the same lines.
  nlohmann::json record;
  std::ifstream(dir / "out/blocks/diffuse/record.json") >> record;
  ASSERT_TRUE(record.contains("warnings")) << record.dump(2);
  EXPECT_EQ(record["warnings"].get<std::vector<std::string>>(), said);
}

// Reused caches say the warnings they were made with again (their pictures are drawn from them), and
// `info` on the output folder counts them on stdout and says so on stderr, --quiet or not.
TEST_F(QuietWarnings, ReusedCachesRenderAndInfoSayTheKeptWarnings) {
  ASSERT_EQ(spume("simulate " + args("--quiet")).status, 0);
  CommandResult r = spume("simulate " + args("--quiet"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(starts_with_any(lines_of(r.err), budget_warning)) << r.err;
  EXPECT_FALSE(contains(r.err, "caches are current")) << r.err;  // a note

  r = spume("render " + args("--quiet"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> rendered = lines_of(r.err);
  EXPECT_EQ(warning_lines(r.err), rendered) << r.err;
  EXPECT_TRUE(starts_with_any(rendered, radius_warning)) << r.err;
  EXPECT_TRUE(starts_with_any(rendered, budget_warning)) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out/blocks/frames/0004.png"));

  r = spume("info --quiet " + (dir / "out/blocks").string());
  ASSERT_EQ(r.status, 0) << r.output << r.err;
  EXPECT_TRUE(contains(r.output, "diffuse caches (diffuse/): frames 1-4, 2 warnings")) << r.output;
  EXPECT_TRUE(contains(r.output, "warnings: 2")) << r.output;
  EXPECT_TRUE(contains(r.output, budget_warning)) << r.output;
  EXPECT_TRUE(contains(r.err, "warning: " + (dir / "out/blocks").string() + ": its outputs were made with 2 warnings"))
      << r.err;
}

// `run` simulates and renders in one process: each warning once, whichever stage gave it first.
TEST_F(QuietWarnings, RunSaysEachWarningOnce) {
  const CommandResult r = spume("run " + args("--quiet"));
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::string> said = lines_of(r.err);
  EXPECT_EQ(warning_lines(r.err), said) << r.err;
  size_t radius = 0, budget = 0;
  for (const std::string& line : said) radius += line.rfind(radius_warning, 0) == 0, budget += line.rfind(budget_warning, 0) == 0;
  EXPECT_EQ(radius, 1u) << r.err;
  EXPECT_EQ(budget, 1u) << r.err;
}

TEST_F(QuietWarnings, LookdevAndFarmKeepTheInputsWarnings) {
  ASSERT_EQ(spume("simulate " + args("--quiet")).status, 0);
  CommandResult r = spume("lookdev " + args("--quiet --vary render.alpha=10,20"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(starts_with_any(lines_of(r.err), radius_warning)) << r.err;
  EXPECT_EQ(warning_lines(r.err), lines_of(r.err)) << r.err;
  // farm slurm reads the inputs to tell whether a simulation job is needed (farm chunks only splits
  // the frames; each chunk's render warns).
  r = spume("farm slurm " + args("--quiet --chunk 2"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(starts_with_any(lines_of(r.err), radius_warning)) << r.err;
  EXPECT_EQ(warning_lines(r.err), lines_of(r.err)) << r.err;
}

// A folder compared with itself passes whatever is in it: compare says so under --quiet.
TEST_F(QuietWarnings, CompareWarnsWhenBothSidesAreTheSameFiles) {
  ASSERT_EQ(spume("run " + args("--quiet")).status, 0);
  const std::string frames = (dir / "out/blocks/frames").string();
  const CommandResult r = spume("compare --quiet " + frames + " " + frames + "/../frames");
  EXPECT_EQ(r.status, 0) << r.output << r.err;
  EXPECT_TRUE(contains(r.err, "warning: REFERENCE " + frames)) << r.err;
  EXPECT_TRUE(contains(r.err, "are the same files: every frame passes")) << r.err;
}

}  // namespace
}  // namespace spume
