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
#include "sim/io/frame_pattern_hint.h"
#include "tests/support/text.h"

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

TEST(Pattern, ParsesEachPlaceholderStyleAndWritesItBack) {
  struct Case {
    const char* pattern;
    const char* prefix;
    int width;
    PlaceholderStyle style;
    const char* suffix;
  };
  for (const Case& c : {Case{"f_%d.ply", "f_", 0, PlaceholderStyle::Printf, ".ply"},
                        Case{"f_%04d.ply", "f_", 4, PlaceholderStyle::Printf, ".ply"},
                        Case{"f_%01d.ply", "f_", 0, PlaceholderStyle::Printf, ".ply"},  // %01d names as %d does
                        Case{"f_####.ply", "f_", 4, PlaceholderStyle::Hashes, ".ply"},
                        Case{"f_#.ply", "f_", 0, PlaceholderStyle::Hashes, ".ply"},
                        Case{"f_$F.ply", "f_", 0, PlaceholderStyle::Houdini, ".ply"},
                        Case{"f_$F4.ply", "f_", 4, PlaceholderStyle::Houdini, ".ply"},
                        Case{"100%%_%d.ply", "100%_", 0, PlaceholderStyle::Printf, ".ply"}}) {
    const FramePatternParts p = parse_frame_pattern(c.pattern);
    EXPECT_EQ(p.prefix, c.prefix) << c.pattern;
    EXPECT_EQ(p.suffix, c.suffix) << c.pattern;
    EXPECT_EQ(p.width, c.width) << c.pattern;
    EXPECT_EQ(int(p.style), int(c.style)) << c.pattern;
  }
  EXPECT_EQ(compose_frame_pattern({"f_", ".ply", 4, PlaceholderStyle::Houdini}), "f_$F4.ply");
  EXPECT_EQ(compose_frame_pattern({"f_", ".ply", 0, PlaceholderStyle::Houdini}), "f_$F.ply");
  EXPECT_EQ(compose_frame_pattern({"f_", ".ply", 3, PlaceholderStyle::Hashes}), "f_###.ply");
  EXPECT_EQ(compose_frame_pattern({"f_", ".ply", 0, PlaceholderStyle::Hashes}), "f_#.ply");
  EXPECT_EQ(compose_frame_pattern({"100%_", ".ply", 2, PlaceholderStyle::Printf}), "100%%_%02d.ply");
  // What a style cannot say falls back to printf: $F stops at 9 digits; "$F" then "1.ply" would read
  // as $F1; a '#' in the text would be a second placeholder beside ####.
  EXPECT_EQ(compose_frame_pattern({"f_", ".ply", 12, PlaceholderStyle::Houdini}), "f_%012d.ply");
  EXPECT_EQ(compose_frame_pattern({"f_", "1.ply", 0, PlaceholderStyle::Houdini}), "f_%d1.ply");
  EXPECT_EQ(compose_frame_pattern({"take#2_", ".ply", 4, PlaceholderStyle::Hashes}), "");
}

TEST(Pattern, TheCanonicalPatternIsTheSameForTheSameFilesTypedDifferently) {
  TempDir dir;
  dir.touch("cache/f_0001.ply");
  fs::create_directory_symlink(dir.path / "cache", dir.path / "link");
  const std::string expected = (fs::canonical(dir.path) / "cache" / "f_%04d.ply").string();
  const fs::path before = fs::current_path();
  fs::current_path(dir.path);
  const std::vector<std::string> typings = {"cache/f_%04d.ply", "./cache/../cache/f_####.ply", "link/f_$F4.ply",
                                            (dir.path / "cache/f_%04d.ply").string()};
  for (const std::string& typed : typings)
    EXPECT_EQ(canonical_frame_pattern(typed), expected) << typed;
  EXPECT_NE(canonical_frame_pattern("cache/f_%d.ply"), expected);  // other files: f_1.ply
  fs::current_path(before);
}

TEST(PatternHint, NamesThePaddingTheFilesHaveInThePatternsOwnStyle) {
  TempDir dir;
  for (int k = 1; k <= 12; ++k) dir.touch(str("padded/f_", k < 10 ? "000" : "00", k, ".ply"));
  for (int k = 3; k <= 5; ++k) dir.touch(str("plain/f_", k, ".ply"));
  const std::string padded = (dir.path / "padded").string() + "/", plain = (dir.path / "plain").string() + "/";
  EXPECT_TRUE(find_pattern_frames(padded + "f_$F.ply").empty());
  struct Case {
    std::string pattern, expected;
  };
  for (const Case& c : {Case{padded + "f_$F.ply", padded + "f_$F4.ply matches 12 files, frames 1-12"},
                        Case{padded + "f_%d.ply", padded + "f_%04d.ply matches 12 files, frames 1-12"},
                        Case{padded + "f_#.ply", padded + "f_####.ply matches 12 files, frames 1-12"},
                        Case{padded + "f_%03d.ply", padded + "f_%04d.ply matches 12 files, frames 1-12"},
                        Case{plain + "f_$F4.ply", plain + "f_$F.ply matches 3 files, frames 3-5"},
                        Case{plain + "f_%04d.ply", plain + "f_%d.ply matches 3 files, frames 3-5"},
                        Case{plain + "f_####.ply", plain + "f_#.ply matches 3 files, frames 3-5"}}) {
    const std::string hint = unmatched_pattern_hint(c.pattern);
    EXPECT_TRUE(contains(hint, c.expected)) << c.pattern << "\n" << hint;
    EXPECT_TRUE(contains(hint, "numbered")) << hint;
  }
  EXPECT_TRUE(contains(unmatched_pattern_hint(padded + "f_$F.ply"), "zero-padded to 4 digits")) << padded;
  EXPECT_TRUE(contains(unmatched_pattern_hint(plain + "f_$F4.ply"), "without zero padding")) << plain;
}

TEST(PatternHint, NamesTheNearestNumberedSequenceOrWhatTheFolderHolds) {
  TempDir dir;
  for (int k = 0; k < 3; ++k) dir.touch(str("case/Fluid_", k, ".bgeo"));
  for (int k = 7; k <= 8; ++k) dir.touch(str("case/mesh_", k, ".obj"));
  const std::string in_case = (dir.path / "case").string() + "/";
  const std::string hint = unmatched_pattern_hint(in_case + "fluid_%d.bgeo");
  // The same name but for a capital comes first, then the other numbered files.
  EXPECT_TRUE(contains(hint, in_case + "Fluid_%d.bgeo matches 3 files, frames 0-2, " + in_case +
                                 "mesh_%d.obj 2 files, frames 7-8")) << hint;

  dir.touch("words/readme.txt");
  dir.touch("words/notes.md");
  const std::string none = unmatched_pattern_hint((dir.path / "words/f_%d.ply").string());
  EXPECT_TRUE(contains(none, "holds 2 files, none numbered (notes.md, readme.txt)")) << none;
  fs::create_directories(dir.path / "empty");
  EXPECT_TRUE(contains(unmatched_pattern_hint((dir.path / "empty/f_%d.ply").string()), "holds no files"));
  // Files that mix paddings (f_1 beside f_0002) have no one pattern: none is named.
  dir.touch("mixed/f_1.ply");
  dir.touch("mixed/f_0002.ply");
  EXPECT_TRUE(contains(unmatched_pattern_hint((dir.path / "mixed/f_%03d.ply").string()), "zero padding mixed"));
}
