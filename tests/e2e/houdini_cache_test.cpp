// Houdini's current geometry through the binary: info on a real .bgeo.sc file, and a frame pattern in
// Houdini's own $F spelling over real files (RBD points standing in for particles).
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::run_spume;

using spume::testing::contains;

const fs::path kCopies = fs::path(SPUME_TEST_DATA_DIR) / "houdini";

TEST(HoudiniCache, InfoDescribesARealBgeoScFile) {
  const CommandResult r = run_spume("info " + (kCopies / "retime_demoscene.10.bgeo.sc").string());
  EXPECT_EQ(r.status, 0) << r.output;
  // The numbers Houdini wrote into the file's own info block: 30 points, one Blosc chunk, packed pieces.
  EXPECT_TRUE(contains(r.output, "points in the file: 30")) << r.output;
  EXPECT_TRUE(contains(r.output, "Blosc-compressed in 1 chunk")) << r.output;
  EXPECT_TRUE(contains(r.output, "(holds the points; it includes the primitives)")) << r.output;
}

TEST(HoudiniCache, AFramePatternInHoudinisSpellingRunsOverRealFiles) {
  testing::TempDir dir;
  fs::create_directories(dir / "cache");
  for (const char* f : {"retime_demoscene.10.bgeo.sc", "retime_demoscene.11.bgeo.sc"})
    fs::copy_file(kCopies / f, dir / "cache" / f);
  // RBD pieces about 0.44 m apart stand in for particles of radius 0.22 m.
  const CommandResult r = run_spume("simulate --quiet --fluid 'cache/retime_demoscene.$F.bgeo.sc' --radius 0.22 --out out",
                                    testing::SpumeOptions::after("cd " + dir.path.string()));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out/retime_demoscene/diffuse/diffuse_0010.spd")) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out/retime_demoscene/diffuse/diffuse_0011.spd")) << r.output;
}

}  // namespace
}  // namespace spume
