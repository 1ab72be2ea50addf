// Image regression: small scenes under tests/golden/ are simulated and rendered by the spume command
// and compared with the golden PNGs committed beside them (tests/golden/<scene>_<frame>.png). The
// rule (image_diff.h): at most 1/255 on all but 0.02% of pixels and 3/255 anywhere; on failure the
// new image, the golden and a x16 difference image are written to out/tests/golden/. After an
// intended change of the pictures, refresh the goldens with
//   SPUME_UPDATE_GOLDENS=1 build/tests/spume_render_tests --gtest_filter='GoldenImages*'
// and look at them before committing.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "image/image_diff.h"
#include "image/png_io.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(SPUME_TEST_DATA_DIR).parent_path() / "golden";

void check_golden(const std::string& scene, int frame) {
  const fs::path out = fs::path(SPUME_OUT_DIR) / "tests" / "golden";
  char name[64];
  std::snprintf(name, sizeof name, "%04d.png", frame);
  const std::string command = std::string(SPUME_BINARY) + " run --quiet " + (kGoldenDir / (scene + ".json")).string() +
                              " --out " + out.string() + " --frames " + std::to_string(frame) + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const ImageRGB8 rendered = read_png(out / scene / "frames" / name);
  const fs::path golden = kGoldenDir / (scene + "_" + name);
  if (std::getenv("SPUME_UPDATE_GOLDENS")) {
    fs::copy_file(out / scene / "frames" / name, golden, fs::copy_options::overwrite_existing);
    GTEST_SKIP() << "golden refreshed: " << golden;
  }
  const ImageRGB8 expected = read_png(golden);
  const ImageDiff diff = compare_images(rendered, expected);
  const bool ok = within_regression_tolerance(diff, rendered.pixel_count());
  if (!ok) {  // the three images side by side in one folder, for a person to look at
    fs::copy_file(out / scene / "frames" / name, out / (scene + "_new.png"), fs::copy_options::overwrite_existing);
    fs::copy_file(golden, out / (scene + "_golden.png"), fs::copy_options::overwrite_existing);
    write_difference_png(out / (scene + "_difference_x16.png"), rendered, expected);
  }
  EXPECT_TRUE(ok) << scene << " frame " << frame << ": " << diff.over_1 << " pixels over 1/255, " << diff.over_3
                  << " over 3/255, max " << diff.max_diff << "/255; difference image in " << out;
}

TEST(GoldenImages, SurfaceSolidsAndDiffuseMaterial) { check_golden("splash", 12); }
TEST(GoldenImages, MarchedDiffuseMaterialOverTheSky) { check_golden("march", 12); }

}  // namespace
}  // namespace spume
