// The container of a one-line --fluid run through the spume binary: inferred only where the fluid
// was seen stopped, and used by default when closed; none around a block falling freely; a given
// tank that leaves the fluid outside is an error; the survey kept beside the outputs is not trusted
// once edited, and is kept with empty frames in it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/support/container_sequences.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;

class TankOption : public ::testing::Test {
 protected:

  // `simulate --fluid PATTERN --radius r` plus `options`; stderr with stdout.
  CommandResult simulate(const std::string& pattern, const std::string& options) const {
    return testing::run_spume("simulate --fluid '" + pattern + "' --radius 0.01 --out " + (dir / "out").string() + " " +
                              options);
  }
  static std::string line_with(const std::string& output, const std::string& text) {
    const size_t at = output.find(text);
    if (at == std::string::npos) return "";
    const size_t begin = output.rfind('\n', at) + 1;
    return output.substr(begin, output.find('\n', at) - begin);
  }
  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

TEST_F(TankOption, ABlockFallingFreelyGetsNoWalls) {
  const std::string pattern = testing::write_sequence(dir / "fall", testing::falling_block());
  // The one-line run: no tank, and the log says why.
  CommandResult r = simulate(pattern, "");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string note = line_with(r.output, "no container inferred");
  EXPECT_NE(note.find("no floor (-y: moves"), std::string::npos) << r.output;
  EXPECT_NE(note.find("+x (no evidence: flat at x = "), std::string::npos) << note;
  EXPECT_NE(note.find("running without a tank"), std::string::npos) << note;
  EXPECT_EQ(r.output.find("container inferred from the fluid"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the fluid's bounds over all 21 frames"), std::string::npos) << r.output;
  // Asked for (--tank auto): an error that says what was measured.
  r = simulate(pattern, "--tank auto");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("the tank to infer (\"infer\": true, or --tank auto): no container inferred: no floor (-y: moves"),
            std::string::npos)
      << r.output;
}

TEST_F(TankOption, TheOneLineRunUsesTheTankTheFluidShowsAndNoneTurnsItOff) {
  const std::string pattern = testing::write_sequence(dir / "column", testing::collapsing_column());
  CommandResult r = simulate(pattern, "");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string note = line_with(r.output, "container inferred from the fluid: walls ");
  ASSERT_NE(note, "") << r.output;
  for (const char* wall : {"-x at 0 (at it from frame 1", "+x at 0.6 (reached in frame 8", "-y at 0 (at it from frame 1",
                           "-z at 0 (", "+z at 0.1 ("})
    EXPECT_NE(note.find(wall), std::string::npos) << wall << ": " << note;
  EXPECT_NE(note.find("used since no --tank was given (--tank none runs without it)"), std::string::npos) << note;
  EXPECT_NE(r.output.find("the tanks (an open one widened on each side and raised"), std::string::npos) << r.output;
  // --tank none: no tank at all, and the caches made with the tank are not current.
  r = simulate(pattern, "--tank none");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("container inferred"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the fluid's bounds over all 16 frames"), std::string::npos) << r.output;
}

TEST_F(TankOption, AnOpenSideKeepsTheOneLineRunWithoutATankButAutoUsesIt) {
  const std::string pattern = testing::write_sequence(dir / "piston", testing::column_at_a_piston());
  CommandResult r = simulate(pattern, "");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string note = line_with(r.output, "container inferred from the fluid: walls ");
  EXPECT_NE(note.find("open: -x (moves: at x = 0.09 in only"), std::string::npos) << r.output;
  EXPECT_NE(note.find("; not used, since a side is open"), std::string::npos) << note;
  EXPECT_NE(r.output.find("the fluid's bounds over all 20 frames"), std::string::npos) << r.output;
  r = simulate(pattern, "--tank auto");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("not used"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("the tanks (an open one widened on each side and raised"), std::string::npos) << r.output;
}

TEST_F(TankOption, AutoAndNoneAreWordsInAnyCaseAndAnythingElseNamesTheChoices) {
  const std::string pattern = testing::write_sequence(dir / "column", testing::collapsing_column());
  for (const char* word : {"'auto '", "AUTO", "' Auto'"}) {
    const CommandResult r = simulate(pattern, std::string("--tank ") + word);
    EXPECT_EQ(r.status, 0) << word << ": " << r.output;
    EXPECT_NE(r.output.find("container inferred from the fluid: walls -x at 0"), std::string::npos) << r.output;
  }
  const CommandResult none = simulate(pattern, "--tank ' NONE'");
  EXPECT_EQ(none.status, 0) << none.output;
  EXPECT_EQ(none.output.find("container inferred"), std::string::npos) << none.output;
  const std::pair<const char*, const char*> bad[] = {
      {"'autom'", "--tank \"autom\": expected auto, none or six numbers x0,y0,z0,x1,y1,z1 (the tank's corners in m); "
                  "\"autom\" is not a number"},
      {"1,2,3", "--tank \"1,2,3\": expected auto, none or six numbers x0,y0,z0,x1,y1,z1 (the tank's corners in m), "
                "found 3 numbers"},
      {"0,0,0,1,x,1", "; \"x\" is not a number"},
  };
  for (const auto& [value, expected] : bad) {
    const CommandResult r = simulate(pattern, std::string("--tank ") + value);
    EXPECT_EQ(r.status, 2) << value << ": " << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << value << ": " << r.output;
  }
}

TEST_F(TankOption, ATankThatDoesNotHoldTheFluidIsAnError) {
  const std::string pattern = testing::write_sequence(dir / "column", testing::collapsing_column());
  const CommandResult r = simulate(pattern, "--tank 10,10,10,11,11,11");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("the tank [10, 10, 10] - [11, 11, 11] m does not hold the fluid: in frame 1, 1000 of its "
                          "1000 particles (100%) lie more than 2r = 0.02 m outside its walls"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "out/fluid/diffuse")) << "nothing simulated";
  // The tank it was made in holds it.
  const CommandResult good = simulate(pattern, "--tank 0,0,0,0.6,1,0.1");
  EXPECT_EQ(good.status, 0) << good.output;
  EXPECT_EQ(good.output.find("outside its walls"), std::string::npos) << good.output;
}

TEST_F(TankOption, AnEditedSurveyIsNotTrusted) {
  const std::string pattern = testing::write_sequence(dir / "column", testing::collapsing_column());
  const CommandResult first = simulate(pattern, "--tank none");
  ASSERT_EQ(first.status, 0) << first.output;
  const std::string domain = line_with(first.output, "domain (diffuse particles leaving it are deleted)");
  ASSERT_NE(domain, "") << first.output;
  // One frame's bounds edited: the domain would grow to hold x = 50.
  const fs::path keep = dir / "out/fluid/fluid_survey.json";
  nlohmann::json j;
  std::ifstream(keep) >> j;
  for (auto& f : j["frames"])
    if (f["frame"] == 5) f["max"][0] = 50.0;
  std::ofstream(keep) << j.dump();
  const CommandResult second = simulate(pattern, "--tank none");
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_NE(second.output.find("fluid_survey.json: 1 entry did not match its digest (edited or damaged); surveyed again"),
            std::string::npos)
      << second.output;
  EXPECT_EQ(line_with(second.output, "domain (diffuse particles leaving it are deleted)"), domain) << second.output;
}

TEST_F(TankOption, EmptyFramesKeepTheSurveyAndLeaveTheTankAsItIs) {
  // Two empty frames before the column (an emitter that starts late); the run starts at frame 3.
  std::vector<std::vector<Vec3f>> frames(2);
  const std::vector<std::vector<Vec3f>> column = testing::collapsing_column();
  frames.insert(frames.end(), column.begin(), column.end());
  const std::string pattern = testing::write_sequence(dir / "late", frames);
  const CommandResult first = simulate(pattern, "--frames 3-18");
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_NE(first.output.find("surveying 18 fluid frames"), std::string::npos) << first.output;
  const std::string note = line_with(first.output, "container inferred from the fluid: walls ");
  EXPECT_NE(note.find("-x at 0 (at it from frame 3"), std::string::npos) << first.output;
  EXPECT_NE(note.find("+x at 0.6 (reached in frame 10"), std::string::npos) << note;
  EXPECT_NE(note.find("-y at 0 ("), std::string::npos) << note;
  // The second run reads nothing again: the survey with its empty frames was kept.
  const CommandResult second = simulate(pattern, "--frames 3-18");
  ASSERT_EQ(second.status, 0) << second.output;
  EXPECT_EQ(second.output.find("surveying"), std::string::npos) << second.output;
  EXPECT_EQ(line_with(second.output, "container inferred from the fluid: walls "), note);
}

}  // namespace
}  // namespace spume
