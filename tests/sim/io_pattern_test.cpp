#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <unistd.h>

#include "sim/core/error.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"
#include "sim/io/frame_pattern.h"

namespace fs = std::filesystem;
using namespace spume;
using namespace spume::testing;

namespace {

}  // namespace

TEST(Pattern, ExpandsEachPlaceholderKind) {
  EXPECT_EQ(expand_frame_pattern("fluid_%d.bgeo", 7), "fluid_7.bgeo");
  EXPECT_EQ(expand_frame_pattern("fluid_%d.bgeo", 0), "fluid_0.bgeo");
  EXPECT_EQ(expand_frame_pattern("fluid_%04d.bgeo", 7), "fluid_0007.bgeo");
  EXPECT_EQ(expand_frame_pattern("fluid_%04d.bgeo", 12345), "fluid_12345.bgeo");  // width is a minimum
  EXPECT_EQ(expand_frame_pattern("fluid_####.bgeo", 12), "fluid_0012.bgeo");
  EXPECT_EQ(expand_frame_pattern("#.ply", 3), "3.ply");
  EXPECT_EQ(expand_frame_pattern("dir/a_%02d_b.vtk", 5), "dir/a_05_b.vtk");
  EXPECT_EQ(expand_frame_pattern("100%%_%d.ply", 5), "100%_5.ply");
}

TEST(Pattern, RecognisesPatterns) {
  EXPECT_TRUE(is_frame_pattern("a_%d.bgeo"));
  EXPECT_TRUE(is_frame_pattern("a_%04d.bgeo"));
  EXPECT_TRUE(is_frame_pattern("a_###.bgeo"));
  EXPECT_FALSE(is_frame_pattern("a_0001.bgeo"));
  EXPECT_FALSE(is_frame_pattern("100%%.bgeo"));
  EXPECT_FALSE(is_frame_pattern("a_%s.bgeo"));
}

TEST(Pattern, RejectsMalformedPatterns) {
  EXPECT_NE(error_of([] { expand_frame_pattern("a_%d_%04d.bgeo", 1); }).find("more than one"), std::string::npos);
  EXPECT_NE(error_of([] { expand_frame_pattern("a_##_%d.bgeo", 1); }).find("more than one"), std::string::npos);
  EXPECT_NE(error_of([] { expand_frame_pattern("a_%5d.bgeo", 1); }).find("'%5d'"), std::string::npos);
  EXPECT_NE(error_of([] { expand_frame_pattern("a_%s.bgeo", 1); }).find("unsupported"), std::string::npos);
  EXPECT_NE(error_of([] { expand_frame_pattern("a.bgeo", 1); }).find("no frame placeholder"), std::string::npos);
  EXPECT_NE(error_of([] { expand_frame_pattern("a_%d.bgeo", -1); }).find("negative"), std::string::npos);
}

TEST(Pattern, FindsExistingFramesSorted) {
  TempDir dir;
  for (const char* name : {"f_0010.bgeo", "f_0001.bgeo", "f_0002.bgeo", "f_12345.bgeo", "f_001.bgeo", "f_00002.bgeo",
                           "f_abcd.bgeo", "g_0003.bgeo", "f_0004.bgeo.tmp", "f_0005.vtk"})
    dir.touch(name);
  const std::vector<int> expected = {1, 2, 10, 12345};
  EXPECT_EQ(find_pattern_frames((dir.path / "f_%04d.bgeo").string()), expected);
  EXPECT_EQ(find_pattern_frames((dir.path / "f_####.bgeo").string()), expected);
}

TEST(Pattern, UnpaddedPatternTakesAnyNumberOfDigits) {
  TempDir dir;
  for (const char* name : {"p_1.ply", "p_2.ply", "p_10.ply", "p_123456.ply", "p_01.ply", "p_.ply", "p_-1.ply"})
    dir.touch(name);
  EXPECT_EQ(find_pattern_frames((dir.path / "p_%d.ply").string()), (std::vector<int>{1, 2, 10, 123456}));
}

TEST(Pattern, FindReportsMissingDirectoryAndBadPlacement) {
  TempDir dir;
  EXPECT_TRUE(find_pattern_frames((dir.path / "none_%d.ply").string()).empty());
  const std::string missing = (dir.path / "nope" / "p_%d.ply").string();
  EXPECT_NE(error_of([&] { find_pattern_frames(missing); }).find("does not exist"), std::string::npos);
  const std::string in_dir = (dir.path / "run_%d" / "p.ply").string();
  EXPECT_NE(error_of([&] { find_pattern_frames(in_dir); }).find("file name"), std::string::npos);
}
