// Nothing silently absurd, third round (issue 44, cases 12-15), through the spume binary: how the fluid
// files are named. A pattern whose padding differs from the files' names the one that matches; a file
// name with a space gives a usable scene name; the same files typed by another path are the same
// input; a key that does not apply to the files changes nothing and is said to; `info` keeps the
// millimetres of a fluid 10 km from the origin.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "sim/io/ply.h"
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

// Four PLY frames (1-4) of two blocks of water on a 0.04 m lattice (radius 0.02 m) thrown at each other,
// written under `folder` as `name` + the frame number zero-padded to `width` digits + ".ply".
void write_frames(const fs::path& folder, const std::string& name, int width) {
  fs::create_directories(folder);
  for (int k = 1; k <= 4; ++k) {
    std::string number = std::to_string(k);
    if (int(number.size()) < width) number.insert(0, size_t(width) - number.size(), '0');
    write_ply(folder / (name + number + ".ply"), testing::blocks_closing_in(k, 0.16f, 0.5f, Vec3f(2, 1, 0)));
  }
}

class InputNaming : public ::testing::Test {
 protected:
  // `spume COMMAND` run from the test's folder, so that relative paths resolve there. Patterns go in
  // single quotes: $F is Houdini's placeholder, not the shell's variable.
  CommandResult spume_here(const std::string& arguments) const {
    return run_spume(arguments, SpumeOptions::after("cd '" + dir.string() + "'"));
  }
  // The modification time of a scene's diffuse record: a run that re-simulates writes it again.
  fs::file_time_type record_time(const std::string& scene) const {
    return fs::last_write_time(dir / "out" / scene / "diffuse" / "record.json");
  }

  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

// Case 12. $F on files numbered 0001..0004 matched nothing, with no hint; now the message names the
// pattern that matches, in the placeholder style the user wrote, and the padding either way.
TEST_F(InputNaming, APatternWithTheWrongPaddingNamesThePatternThatMatches) {
  write_frames(dir / "padded", "f_", 4);
  write_frames(dir / "plain", "f_", 0);
  struct Case {
    std::string given, matching, padding;
  };
  for (const Case& c : {Case{"padded/f_$F.ply", "padded/f_$F4.ply", "zero-padded to 4 digits"},
                        Case{"padded/f_%d.ply", "padded/f_%04d.ply", "zero-padded to 4 digits"},
                        Case{"padded/f_#.ply", "padded/f_####.ply", "zero-padded to 4 digits"},
                        Case{"plain/f_$F4.ply", "plain/f_$F.ply", "without zero padding"},
                        Case{"plain/f_%04d.ply", "plain/f_%d.ply", "without zero padding"},
                        Case{"plain/f_####.ply", "plain/f_#.ply", "without zero padding"}}) {
    const CommandResult r = spume_here("simulate --fluid '" + c.given + "' --radius 0.02 --out out");
    EXPECT_EQ(r.status, 1) << c.given << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, c.given + ": no files match this pattern")) << r.output;
    EXPECT_TRUE(contains(r.output, "the files there are numbered " + c.padding)) << r.output;
    EXPECT_TRUE(contains(r.output, c.matching + " matches 4 files, frames 1-4")) << r.output;
  }
  // The pattern it names is one that runs.
  const CommandResult fixed = spume_here("simulate --fluid 'padded/f_$F4.ply' --radius 0.02 --out out");
  EXPECT_EQ(fixed.status, 0) << fixed.output;
}

// Case 13. "my fluid %04d.ply" made the scene name "my fluid " and stopped; now the name is made usable
// (my_fluid), the log says so and how to give another; a name given by the key is not altered but
// refused with a usable one to take.
TEST_F(InputNaming, AFileNameWithSpacesGivesAUsableSceneName) {
  write_frames(dir / "in put", "my fluid ", 4);
  const CommandResult r = spume_here("simulate --fluid 'in put/my fluid %04d.ply' --radius 0.02 --out out");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "scene name: my_fluid, the folder of its results (taken from the file name \"my "
                                 "fluid \", which is not a usable folder name")) << r.output;
  EXPECT_TRUE(contains(r.output, "--set name=NAME")) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out/my_fluid/diffuse/record.json"));

  const CommandResult named =
      spume_here("simulate --fluid 'in put/my fluid %04d.ply' --radius 0.02 --out out --set 'name=my fluid'");
  EXPECT_EQ(named.status, 1) << named.output;
  EXPECT_TRUE(contains(named.output, "\"my fluid\" is not a usable folder name")) << named.output;
  EXPECT_TRUE(contains(named.output, "e.g. \"my_fluid\"")) << named.output;

  // A scene file's name with a space: the same.
  std::ofstream(dir / "my scene.json") << R"({"fluid": {"files": "in put/my fluid %04d.ply", "radius": 0.02}})";
  const CommandResult scene = spume_here("simulate 'my scene.json' --out out");
  ASSERT_EQ(scene.status, 0) << scene.output;
  EXPECT_TRUE(fs::exists(dir / "out/my_scene/diffuse/record.json"));
}

// Case 14. Simulated with a relative path, rendered with an absolute one: render refused ("not current:
// key fluid.files"). The same files are the same input however typed (relative, absolute, through
// "./", with $F for %d); other files at the same size and time are not.
TEST_F(InputNaming, TheSameFilesTypedByAnotherPathAreTheSameInput) {
  write_frames(dir / "cache", "f_", 0);
  ASSERT_EQ(spume_here("simulate --fluid 'cache/f_%d.ply' --radius 0.02 --out out").status, 0);
  const fs::file_time_type made = record_time("f");
  const std::string absolute = (dir / "." / "cache" / "f_$F.ply").string();

  const CommandResult again = spume_here("simulate --fluid '" + absolute + "' --radius 0.02 --out out");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_FALSE(contains(again.output, "diffuse: simulating")) << again.output;
  EXPECT_EQ(record_time("f"), made);

  const CommandResult render = spume_here("render --fluid '" + absolute + "' --radius 0.02 --out '" +
                                          (dir / "out").string() + "' --set 'render.resolution=[64,36]'");
  EXPECT_EQ(render.status, 0) << render.output;
  EXPECT_FALSE(contains(render.output, "not current")) << render.output;

  // A copy with the same sizes and times is other files: simulated again, naming the key.
  fs::create_directories(dir / "copy");
  for (int k = 1; k <= 4; ++k) {
    const std::string name = "f_" + std::to_string(k) + ".ply";
    fs::copy_file(dir / "cache" / name, dir / "copy" / name);
    fs::last_write_time(dir / "copy" / name, fs::last_write_time(dir / "cache" / name));
  }
  const CommandResult other = spume_here("simulate --fluid 'copy/f_%d.ply' --radius 0.02 --out out");
  ASSERT_EQ(other.status, 0) << other.output;
  EXPECT_TRUE(contains(other.output, "diffuse: simulating (key fluid.files: ")) << other.output;
}

// Case 15, first half. fluid.vdb_grid on PLY files was ignored, yet changing it simulated again; now
// the run says it does not apply, and the caches stay current.
TEST_F(InputNaming, AVdbGridKeyOnPlyFilesIsSaidNotToApplyAndChangesNothing) {
  write_frames(dir / "cache", "f_", 0);
  ASSERT_EQ(spume_here("simulate --fluid 'cache/f_%d.ply' --radius 0.02 --out out").status, 0);
  const fs::file_time_type made = record_time("f");
  const CommandResult r =
      spume_here("simulate --fluid 'cache/f_%d.ply' --radius 0.02 --out out --set fluid.vdb_grid=density");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "warning: fluid.vdb_grid \"density\" does not apply to f_%d.ply")) << r.output;
  EXPECT_FALSE(contains(r.output, "diffuse: simulating")) << r.output;
  EXPECT_EQ(record_time("f"), made);
}

// Case 15, second half. `info` printed a fluid 10 km from the origin with 6 significant digits
// (10000, a 10 cm step); now its bounds keep 0.1 mm. The corners are floats (2^-10 m apart near 1e4):
// 10000 + 5/1024 = 10000.0048828125, printed to 4 decimals.
TEST_F(InputNaming, InfoKeepsTheMillimetresOfAFluidTenKilometresOut) {
  FluidFrame far;
  const float offset = 5.0f / 1024;
  far.positions = {Vec3f(10000.0f + offset, 1.0f, 10000.0f - offset), Vec3f(10000.5f + offset, 1.25f, 10000.5f)};
  write_ply(dir / "far.ply", far);
  const CommandResult r = spume_here("info far.ply");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "bounds: (10000.0049, 1, 9999.9951) .. (10000.5049, 1.25, 10000.5)")) << r.output;
}

}  // namespace
}  // namespace spume
