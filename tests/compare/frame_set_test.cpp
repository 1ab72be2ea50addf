// Which frames `spume compare` pairs up: two files, folders matched by name (and a scene's output
// folder meaning its frames/), patterns matched by number, --frames, and the usage errors.
#include <gtest/gtest.h>

#include "render/app/compare/frame_set.h"
#include "tests/compare/compare_test_support.h"

namespace spume::compare {
namespace {

namespace fs = std::filesystem;
using testing::fresh_dir;
using testing::write_file;

// resolve_frames only lists files; their contents are read later, so empty files do here.
void touch(const fs::path& p) { write_file(p, ""); }

TEST(FrameSet, TwoFiles) {
  const fs::path dir = fresh_dir("set_files");
  touch(dir / "a.png"), touch(dir / "b.png");
  const FrameSet s = resolve_frames((dir / "a.png").string(), (dir / "b.png").string(), std::nullopt);
  EXPECT_EQ(s.mode, FrameSet::Mode::files);
  ASSERT_EQ(s.frames.size(), 1u);
  EXPECT_EQ(s.frames[0].label, "a.png");
  EXPECT_TRUE(s.frames[0].has_reference && s.frames[0].has_candidate);
  EXPECT_THROW(resolve_frames((dir / "a.png").string(), (dir / "b.png").string(), "0-3"), UsageError);
}

TEST(FrameSet, FoldersMatchByNameInNaturalOrder) {
  const fs::path dir = fresh_dir("set_folders");
  for (const char* n : {"f_2.png", "f_10.png", "f_1.png", "only_ref.png", "notes.txt"}) touch(dir / "ref" / n);
  for (const char* n : {"f_2.png", "f_10.png", "f_1.png", "only_new.PNG"}) touch(dir / "new" / n);
  const FrameSet s = resolve_frames((dir / "ref").string(), (dir / "new").string(), std::nullopt);
  EXPECT_EQ(s.mode, FrameSet::Mode::folders);
  ASSERT_EQ(s.frames.size(), 5u);
  EXPECT_EQ(s.frames[0].label, "f_1.png");
  EXPECT_EQ(s.frames[1].label, "f_2.png");
  EXPECT_EQ(s.frames[2].label, "f_10.png");
  EXPECT_EQ(s.frames[2].number, 10);
  EXPECT_EQ(s.frames[3].label, "only_new.PNG");
  EXPECT_FALSE(s.frames[3].has_reference);
  EXPECT_TRUE(s.frames[3].has_candidate);
  EXPECT_EQ(s.frames[3].reference, dir / "ref" / "only_new.PNG");  // where it would be: named in the report
  EXPECT_EQ(s.frames[4].label, "only_ref.png");
  EXPECT_FALSE(s.frames[4].has_candidate);
  // --frames selects by the trailing number.
  const FrameSet two = resolve_frames((dir / "ref").string(), (dir / "new").string(), "2-10");
  ASSERT_EQ(two.frames.size(), 2u);
  EXPECT_EQ(two.frames[0].label, "f_2.png");
  EXPECT_EQ(two.frames[1].label, "f_10.png");
}

TEST(FrameSet, SceneOutputFolderMeansItsFrames) {
  const fs::path dir = fresh_dir("set_scene");
  touch(dir / "ref" / "wave" / "frames" / "0000.png");
  touch(dir / "new" / "wave" / "frames" / "0000.png");
  touch(dir / "ref" / "wave" / "stats.csv");
  const FrameSet s = resolve_frames((dir / "ref" / "wave").string(), (dir / "new" / "wave").string(), std::nullopt);
  ASSERT_EQ(s.frames.size(), 1u);
  EXPECT_EQ(s.reference_source, (dir / "ref" / "wave" / "frames").string());
  EXPECT_EQ(s.notes.size(), 2u);
}

TEST(FrameSet, PatternsMatchByNumberAndNameMissingFrames) {
  const fs::path dir = fresh_dir("set_patterns");
  for (int f : {0, 1, 2, 5}) touch(dir / "ref" / ("r" + std::to_string(f) + ".png"));
  for (int f : {0, 2, 3, 5}) {
    char name[32];
    std::snprintf(name, sizeof name, "%04d.png", f);
    touch(dir / "new" / name);
  }
  const FrameSet s = resolve_frames((dir / "ref" / "r%d.png").string(), (dir / "new" / "%04d.png").string(), std::nullopt);
  EXPECT_EQ(s.mode, FrameSet::Mode::patterns);
  ASSERT_EQ(s.frames.size(), 5u);  // 0 1 2 3 5: frames on either side; 4 is on neither
  EXPECT_EQ(s.frames[1].number, 1);
  EXPECT_FALSE(s.frames[1].has_candidate);
  EXPECT_EQ(s.frames[1].candidate, dir / "new" / "0001.png");
  EXPECT_FALSE(s.frames[3].has_reference);
  EXPECT_EQ(s.frames[3].reference, dir / "ref" / "r3.png");
  // Asked for explicitly, frame 4 is missing on both sides; 6 lies beyond every frame found.
  const FrameSet asked = resolve_frames((dir / "ref" / "r%d.png").string(), (dir / "new" / "%04d.png").string(), "3-6");
  ASSERT_EQ(asked.frames.size(), 3u);
  EXPECT_EQ(asked.frames[1].number, 4);
  EXPECT_FALSE(asked.frames[1].has_reference || asked.frames[1].has_candidate);
  // A folder opposite a pattern takes the pattern's file name.
  const FrameSet mixed = resolve_frames((dir / "new").string(), (dir / "ref" / "r%d.png").string(), std::nullopt);
  EXPECT_EQ(mixed.reference_source, (dir / "new" / "r%d.png").string());
  EXPECT_EQ(mixed.mode, FrameSet::Mode::patterns);
}

TEST(FrameSet, UsageErrorsNameTheArgument) {
  const fs::path dir = fresh_dir("set_errors");
  touch(dir / "a.png");
  fs::create_directories(dir / "empty1"), fs::create_directories(dir / "empty2");
  auto message = [](const std::string& ref, const std::string& cand, std::optional<std::string> spec = std::nullopt) {
    try {
      resolve_frames(ref, cand, spec);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message((dir / "nope").string(), (dir / "a.png").string()).find("REFERENCE " + (dir / "nope").string() + ": no such file"), std::string::npos);
  EXPECT_NE(message((dir / "a.png").string(), (dir / "empty1").string()).find("is a file but NEW"), std::string::npos);
  EXPECT_NE(message((dir / "empty1").string(), (dir / "empty2").string()).find("no PNG files"), std::string::npos);
  EXPECT_NE(message((dir / "x%d.png").string(), (dir / "y%d.png").string()).find("no frames match"), std::string::npos);
  EXPECT_NE(message((dir / "gone" / "%d.png").string(), (dir / "empty1").string()).find("does not exist"), std::string::npos);
  EXPECT_NE(message((dir / "a.png").string(), (dir / "a.png").string(), "1").find("--frames"), std::string::npos);
  EXPECT_NE(message("", (dir / "a.png").string()).find("REFERENCE is empty"), std::string::npos);
}

TEST(FrameSet, StemsAreSafeAndUnique) {
  const fs::path dir = fresh_dir("set_stems");
  for (const char* n : {"a b.png", "a_b.png", "x#1.png"}) touch(dir / "ref" / n), touch(dir / "new" / n);
  const FrameSet s = resolve_frames((dir / "ref").string(), (dir / "new").string(), std::nullopt);
  ASSERT_EQ(s.frames.size(), 3u);
  EXPECT_EQ(s.frames[0].stem, "a_b");
  EXPECT_EQ(s.frames[1].stem, "a_b_2");
  EXPECT_EQ(s.frames[2].stem, "x_1");
}

TEST(FrameSet, NaturalOrder) {
  EXPECT_TRUE(natural_less("f2.png", "f10.png"));
  EXPECT_FALSE(natural_less("f10.png", "f2.png"));
  EXPECT_TRUE(natural_less("f0002.png", "f10.png"));
  EXPECT_TRUE(natural_less("a.png", "b.png"));
  EXPECT_TRUE(natural_less("f7", "f007"));
  EXPECT_FALSE(natural_less("f7", "f7"));
  EXPECT_TRUE(natural_less("f", "f1"));
}

}  // namespace
}  // namespace spume::compare
