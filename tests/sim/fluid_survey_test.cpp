// The survey of a fluid sequence (io/fluid_survey.h): each frame's count, bounds and sheets from
// hand-worked positions; what is kept beside the outputs is reused only for unchanged files and
// only when it is the survey's own (an edited entry is surveyed again); empty frames are kept too.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "sim/io/fluid_survey.h"
#include "sim/io/ply.h"
#include "tests/support/test_fluids.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

TEST(SurveyPositions, CountsBoundsAndTheFourthOutermostPerSide) {
  // Ten particles along x at 0..9, y = x^2 / 10, z = -x: the 4th lowest / highest of each coordinate.
  std::vector<Vec3f> p;
  for (int i = 0; i < 10; ++i) p.emplace_back(float(i), float(i * i) / 10.0f, -float(i));
  const FrameSurvey f = survey_positions(p);
  EXPECT_EQ(f.particles, 10u);
  EXPECT_EQ(f.bounds.min, Vec3f(0, 0, -9));
  EXPECT_EQ(f.bounds.max, Vec3f(9, 8.1f, 0));
  const float expected[6] = {3, 6, 0.9f, 3.6f, -6, -3};
  for (size_t side = 0; side < 6; ++side) EXPECT_FLOAT_EQ(f.sheet[side], expected[side]) << side;
  EXPECT_TRUE(f.has_sheet());
  EXPECT_FLOAT_EQ(f.centroid.x(), 4.5f);
  EXPECT_FLOAT_EQ(f.centroid.y(), 2.85f);  // (0 + 1 + 4 + ... + 81) / 10 / 10
  EXPECT_FLOAT_EQ(f.centroid.z(), -4.5f);
}

TEST(SurveyPositions, AnEmptyFrameHasNoBoundsAndNoSheet) {
  const FrameSurvey f = survey_positions({});
  EXPECT_EQ(f.particles, 0u);
  EXPECT_TRUE(f.bounds.empty());
  EXPECT_FALSE(f.has_sheet());
  for (float s : f.sheet) EXPECT_TRUE(std::isnan(s));  // not 0: that would be a plane at 0
  EXPECT_TRUE(std::isnan(f.centroid.x()));
}

TEST(SurveyPositions, MedianSpacingOfALattice) {
  EXPECT_NEAR(median_spacing(testing::lattice(Vec3f::Zero(), Vec3f(0.3f, 0.3f, 0.3f), 0.03f)), 0.03f, 1e-6f);
}

class SurveyFiles : public ::testing::Test {
 protected:
  // Frame k: a 3 x 3 x 3 lattice (spacing 0.02) shifted by k * 0.1 along x; `empty` frames hold none.
  void write_frame(int k, bool empty = false, float shift = 0.1f) {
    FluidFrame f;
    if (!empty) f.positions = testing::lattice(Vec3f(shift * float(k), 0, 0), Vec3f(shift * float(k) + 0.04f, 0.04f, 0.04f), 0.02f);
    write_ply(path(k), f);
  }
  // Rewrites frame k with other content of the same size and puts its modification time back: its
  // identity (size and time) is unchanged, so a kept entry is used, and the bounds show which.
  void replace_keeping_identity(int k, float shift) {
    const auto time = fs::last_write_time(path(k));
    write_frame(k, false, shift);
    fs::last_write_time(path(k), time);
  }
  fs::path path(int k) const { return dir / ("p_" + std::to_string(k) + ".ply"); }
  std::string pattern() const { return (dir / "p_%d.ply").string(); }
  fs::path keep() const { return dir / "fluid_survey.json"; }

  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

TEST_F(SurveyFiles, KeptEntriesAreReusedForUnchangedFiles) {
  for (int k = 1; k <= 4; ++k) write_frame(k);
  const FluidSurvey first = survey_fluid_files(pattern(), {1, 2, 3, 4}, keep(), true);
  EXPECT_NEAR(first.frames[2].bounds.min.x(), 0.3f, 1e-6f);
  EXPECT_NEAR(first.spacing, 0.02f, 1e-6f);
  replace_keeping_identity(3, 0.5f);
  const FluidSurvey second = survey_fluid_files(pattern(), {1, 2, 3, 4}, keep(), true);
  EXPECT_NEAR(second.frames[2].bounds.min.x(), 0.3f, 1e-6f);  // the kept entry, not the file
  EXPECT_TRUE(second.notes.empty());
  fs::remove(path(3));  // a changed file is surveyed again
  write_frame(3, false, 0.7f);
  const FluidSurvey third = survey_fluid_files(pattern(), {1, 2, 3, 4}, keep(), true);
  EXPECT_NEAR(third.frames[2].bounds.min.x(), 2.1f, 1e-5f);
}

TEST_F(SurveyFiles, EmptyFramesAreKeptAcrossRuns) {
  write_frame(1, true);
  for (int k = 2; k <= 5; ++k) write_frame(k);
  write_frame(6, true);
  const FluidSurvey first = survey_fluid_files(pattern(), {1, 2, 3, 4, 5, 6}, keep(), true);
  EXPECT_EQ(first.frames[0].particles, 0u);
  EXPECT_FALSE(first.frames[0].has_sheet());
  EXPECT_NEAR(first.bounds().min.x(), 0.2f, 1e-6f);  // empty frames add nothing
  EXPECT_NEAR(first.bounds().max.x(), 0.54f, 1e-6f);
  // The kept file is valid JSON with no null in it, and a second run takes every entry from it.
  std::ifstream in(keep());
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("null"), std::string::npos) << text;
  replace_keeping_identity(4, 0.5f);
  const FluidSurvey second = survey_fluid_files(pattern(), {1, 2, 3, 4, 5, 6}, keep(), true);
  EXPECT_NEAR(second.frames[3].bounds.min.x(), 0.4f, 1e-6f);  // kept, so the survey was not thrown away
  EXPECT_EQ(second.frames[0].particles, 0u);
  EXPECT_FALSE(second.frames[5].has_sheet());
  EXPECT_TRUE(second.notes.empty());
}

TEST_F(SurveyFiles, AnEditedEntryIsNotTrusted) {
  for (int k = 1; k <= 4; ++k) write_frame(k);
  survey_fluid_files(pattern(), {1, 2, 3, 4}, keep(), true);
  // Frame 2's bounds edited by hand: its file is unchanged, its entry no longer matches its digest.
  nlohmann::json j;
  std::ifstream(keep()) >> j;
  for (auto& f : j["frames"])
    if (f["frame"] == 2) f["max"][0] = 50.0;
  std::ofstream(keep()) << j.dump();
  const FluidSurvey again = survey_fluid_files(pattern(), {1, 2, 3, 4}, keep(), true);
  EXPECT_NEAR(again.frames[1].bounds.max.x(), 0.24f, 1e-6f);
  EXPECT_NEAR(again.bounds().max.x(), 0.44f, 1e-6f);
  ASSERT_EQ(again.notes.size(), 1u);
  EXPECT_NE(again.notes[0].find("1 entry did not match its digest"), std::string::npos) << again.notes[0];
  // The edited spacing is not trusted either.
  std::ifstream(keep()) >> j;
  j["spacing"] = 5.0;
  std::ofstream(keep()) << j.dump();
  EXPECT_NEAR(survey_fluid_files(pattern(), {1, 2, 3, 4}, keep(), true).spacing, 0.02f, 1e-6f);
}

}  // namespace
}  // namespace spume
