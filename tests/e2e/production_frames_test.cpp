// Frames for a production pipeline through the binary. EXR frames (`render --exr`, frame/frame_exr.h),
// read by OpenImageIO's tools as a compositor's pipeline would: the layers it lists, put back together
// with oiiotool in the order the header gives, rebuild beauty; the header carries the PNG's record;
// turning the export off removes the files of an earlier run and leaves the PNGs alone. Motion blur
// (render.shutter): a frame drawn again with it, the same bytes for any thread count, and lookdev.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "render/image/exr_io.h"
#include "render/image/png_io.h"
#include "tests/support/run_command.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "sim/io/bgeo.h"
#include "tests/support/blocks_scene.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::run_spume;

// The blocks scene (spray, foam and bubbles), drawn small.
class ProductionFrames : public ::testing::Test {
 protected:
  void SetUp() override { testing::write_blocks_scene(dir, R"({"resolution": [120, 80], "alpha": 400})"); }
  std::string args(const std::string& more = "", const std::string& out_dir = "out") const {
    return (dir / "scene.json").string() + " --out " + (dir / out_dir).string() + " " + more;
  }
  fs::path frame(int k, const char* ext, const std::string& out_dir = "out") const {
    char name[32];
    std::snprintf(name, sizeof name, "frames/%04d%s", k, ext);
    return dir / out_dir / "blocks" / name;
  }

  const testing::TempDir temp{"production_frames"};
  const fs::path& dir = temp.path;
};

TEST_F(ProductionFrames, OiiotoolListsTheLayersAndRebuildsBeautyFromThemInTheHeadersOrder) {
  const CommandResult made = run_spume("run " + args("--quiet --exr --frames 6-8"));
  ASSERT_EQ(made.status, 0) << made.output;
  const fs::path exr = frame(8, ".exr");
  const CommandResult info = testing::run_command("iinfo -v " + exr.string() + " 2>&1");
  ASSERT_EQ(info.status, 0) << info.output;
  for (const char* channel : {"R (half)", "A (half)", "Z (float)", "sky.R (half)", "opaque.A (half)", "water.G (half)",
                              "spray.A (half)", "foam.R (half)", "bubble.B (half)", "forward.u (half)",
                              "backward.v (half)"})
    EXPECT_NE(info.output.find(channel), std::string::npos) << channel << " missing from:\n" << info.output;
  EXPECT_NE(info.output.find("(spray + foam + bubble) over water over opaque over sky"), std::string::npos) << info.output;

  // The record beside the pixels is the PNG's: both were drawn from the same keys and caches.
  const std::optional<std::string> png_record = read_png_record(frame(8, ".png"));
  ASSERT_TRUE(png_record);
  const ExrContents frame8 = read_exr(exr);
  EXPECT_EQ(frame8.strings.at("spume/record"), *png_record);
  EXPECT_EQ(frame8.strings.at("spume/scene"), "blocks");
  const CommandResult described = run_spume("info " + exr.string());
  EXPECT_EQ(described.status, 0) << described.output;
  for (const char* line : {"OpenEXR, 120x80, zip, 33 channels", "spray: A B G R; covers", "spume/scene: blocks"})
    EXPECT_NE(described.output.find(line), std::string::npos) << line << " missing from:\n" << described.output;

  // oiiotool: the diffuse layers added, then over water, over opaque, over sky.
  auto layer = [&](const char* l) {
    return exr.string() + " --ch R=" + l + ".R,G=" + l + ".G,B=" + l + ".B,A=" + l + ".A ";
  };
  const fs::path rebuilt = dir / "rebuilt.exr";
  const CommandResult comp = testing::run_command(
      "oiiotool " + layer("spray") + layer("foam") + "--add " + layer("bubble") + "--add " + layer("water") +
      layer("opaque") + layer("sky") + "--over --over --over -d float -o " + rebuilt.string() + " 2>&1");
  ASSERT_EQ(comp.status, 0) << comp.output;
  const ExrContents r = read_exr(rebuilt);
  ASSERT_EQ(r.width, 120);
  // Each term is rounded to half (2^-11 of its size) and all terms are >= 0: the sum is within a few
  // of those roundings of the value. Tolerance: 0.2% of the value, at least 1e-4.
  double worst = 0.0;
  size_t diffuse_pixels = 0;
  for (const char* c : {"R", "G", "B", "A"}) {
    const std::vector<float>&got = r.channels.at(c), &want = frame8.channels.at(c);
    for (size_t p = 0; p < got.size(); ++p)
      worst = std::max(worst, std::abs(double(got[p]) - want[p]) / std::max(double(std::abs(want[p])), 0.05));
  }
  for (size_t p = 0; p < size_t(120 * 80); ++p)
    diffuse_pixels += frame8.channels.at("spray.A")[p] + frame8.channels.at("foam.A")[p] +
                          frame8.channels.at("bubble.A")[p] > 0.05f;
  EXPECT_LT(worst, 2e-3) << "largest error relative to the value";
  EXPECT_GT(diffuse_pixels, 50u) << "the frame should show diffuse material";
  // Beauty is opaque; Z is finite and within the scene where anything was drawn.
  for (size_t p = 0; p < size_t(120 * 80); ++p) ASSERT_EQ(frame8.channels.at("A")[p], 1.0f);
  const auto [z_min, z_max] = std::minmax_element(frame8.channels.at("Z").begin(), frame8.channels.at("Z").end());
  EXPECT_GT(*z_min, 0.1f);
  EXPECT_LE(*z_max, 1e10f);
}

TEST_F(ProductionFrames, OffRemovesAnEarlierRunsFilesAndLeavesThePngsCurrent) {
  const CommandResult made = run_spume("run " + args("--quiet --exr --frames 7-8"));
  ASSERT_EQ(made.status, 0) << made.output;
  ASSERT_TRUE(fs::exists(frame(7, ".exr")) && fs::exists(frame(8, ".exr")));
  const auto png_time = fs::last_write_time(frame(8, ".png"));

  CommandResult r = run_spume("render " + args("--frames 7-8"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("removed 2 EXR frames of an earlier run (render.exr is off)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("0 frames written, 2 current"), std::string::npos) << "the export is not part of the picture";
  EXPECT_FALSE(fs::exists(frame(7, ".exr")) || fs::exists(frame(8, ".exr")));
  EXPECT_EQ(fs::last_write_time(frame(8, ".png")), png_time);

  // Back on: a frame whose EXR is missing is drawn again; then both are current.
  r = run_spume("render " + args("--exr --frames 7-8"));
  EXPECT_NE(r.output.find("2 frames written"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(frame(8, ".exr")));
  r = run_spume("render " + args("--exr --frames 7-8"));
  EXPECT_NE(r.output.find("0 frames written, 2 current"), std::string::npos) << r.output;

  // Other keys: the EXR follows them, as the PNG does.
  const std::string before = *read_exr_string(frame(8, ".exr"), "spume/record");
  r = run_spume("render " + args("--exr --frames 8 --set render.alpha=200"));
  EXPECT_NE(r.output.find("1 frames written"), std::string::npos) << r.output;
  EXPECT_NE(*read_exr_string(frame(8, ".exr"), "spume/record"), before);
  EXPECT_EQ(*read_exr_string(frame(8, ".exr"), "spume/record"), *read_png_record(frame(8, ".png")));
}

TEST_F(ProductionFrames, ThePixelsDoNotDependOnTheThreadCount) {
  const CommandResult on_one = run_spume("run " + args("--quiet --exr --frames 8 --threads 1", "one"));
  ASSERT_EQ(on_one.status, 0) << on_one.output;
  const CommandResult on_two = run_spume("run " + args("--quiet --exr --frames 8 --threads 2", "two"));
  ASSERT_EQ(on_two.status, 0) << on_two.output;
  const ExrContents one = read_exr(frame(8, ".exr", "one")), two = read_exr(frame(8, ".exr", "two"));
  ASSERT_EQ(one.channels.size(), 33u) << "beauty, Z, 6 layers, 4 motion channels";
  for (const auto& [name, values] : one.channels) EXPECT_EQ(values, two.channels.at(name)) << name;
}

// A cache without velocities gives the water no motion vectors; the run says so rather than writing
// still water as if it had measured it.
TEST_F(ProductionFrames, FluidFilesWithoutVelocitiesAreSaidToLeaveTheWaterStill) {
  for (int k = 1; k <= 8; ++k) {
    FluidFrame f = testing::blocks_closing_in(k, 0.16f, 0.5f, Vec3f(2.0f, 1, 0));
    f.velocities.clear();
    write_bgeo(dir / "cache" / ("fluid_" + std::to_string(k) + ".bgeo"), f);
  }
  CommandResult r = run_spume("run " + args("--quiet --frames 8"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("motion vectors"), std::string::npos) << "no EXR asked for: nothing to say";
  r = run_spume("render " + args("--quiet --frames 8 --exr"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("hold no velocities, so the EXR frames' motion vectors show the water still"),
            std::string::npos) << r.output;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_F(ProductionFrames, TheShutterRedrawsTheFrameTheSameForAnyThreadCountAndLookdevVariesIt) {
  ASSERT_EQ(run_spume("run " + args("--quiet --frames 8")).status, 0);
  const std::string still = file_bytes(frame(8, ".png"));
  CommandResult r = run_spume("render " + args("--frames 8 --threads 1 --set render.shutter=0.5"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("1 frames written"), std::string::npos) << "the shutter is part of the picture";
  const std::string one = file_bytes(frame(8, ".png"));
  EXPECT_NE(one, still);
  ASSERT_EQ(run_spume("render " + args("--quiet --frames 8 --threads 2 --overwrite --set render.shutter=0.5")).status, 0);
  EXPECT_EQ(file_bytes(frame(8, ".png")), one) << "two threads drew other bytes than one";

  const fs::path sheet = dir / "sheet.png";
  r = run_spume("lookdev " + args("--quiet --frame 8 --vary render.shutter=0,1 --output " + sheet.string()));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(sheet));

  r = run_spume("render " + args("--frames 8 --set render.shutter=0.5 --set render.integrator=march"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("render.shutter"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("render.integrator \"exact\""), std::string::npos) << r.output;
}

}  // namespace
}  // namespace spume
