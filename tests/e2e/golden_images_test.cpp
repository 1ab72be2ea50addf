// Image regression: small scenes under tests/golden/ are simulated and rendered by the spume command
// and compared with the golden PNGs committed beside them (tests/golden/<scene>_<frame>.png) through
// `spume compare`'s own code and default thresholds (image_compare.h): at most 1/255 on all but 0.02%
// of pixels and 3/255 anywhere. On failure the comparison's report (report.html with the reference,
// the new image, the x16 difference and the heat map; summary.csv and summary.json) is written to
// out/tests/golden/<scene>_compare/. After an intended change of the pictures, refresh the goldens with
//   SPUME_UPDATE_GOLDENS=1 build/tests/spume_e2e_tests --gtest_filter='GoldenImages*'
// and look at them before committing.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "render/app/compare/compare_report.h"
#include "tests/support/run_spume.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

const fs::path kGoldenDir = fs::path(SPUME_TEST_DATA_DIR).parent_path() / "golden";

void check_golden(const std::string& scene, int frame) {
  const fs::path out = fs::path(SPUME_OUT_DIR) / "tests" / "golden";
  char name[64];
  std::snprintf(name, sizeof name, "%04d.png", frame);
  // From scratch: caches an older build left in out/ are still valid to spume (version 1 caches are read),
  // but the golden is what this build makes.
  fs::remove_all(out / scene);
  const testing::CommandResult run = testing::run_spume("run --quiet " + (kGoldenDir / (scene + ".json")).string() +
                                                       " --out " + out.string() + " --frames " + std::to_string(frame));
  ASSERT_EQ(run.status, 0) << run.output;
  const fs::path rendered = out / scene / "frames" / name;
  const fs::path golden = kGoldenDir / (scene + "_" + name);
  if (std::getenv("SPUME_UPDATE_GOLDENS")) {
    fs::copy_file(rendered, golden, fs::copy_options::overwrite_existing);
    GTEST_SKIP() << "golden refreshed: " << golden;
  }
  // `spume compare GOLDEN RENDERED`: the golden is the reference.
  const compare::FrameSet set = compare::resolve_frames(golden.string(), rendered.string(), std::nullopt);
  compare::CompareOptions options;  // the defaults are the regression rule
  const compare::FrameResult result = compare::compare_and_report(set, options).front();
  const fs::path report = out / (scene + "_compare");
  if (!result.passed()) {  // again with the report, for a person to look at
    options.out = report;
    compare::compare_and_report(set, options);
  }
  EXPECT_TRUE(result.passed()) << scene << " frame " << frame << ": " << result.reason << "; report: "
                               << (report / "report.html");
}

TEST(GoldenImages, SurfaceSolidsAndDiffuseMaterial) { check_golden("splash", 12); }
TEST(GoldenImages, MarchedDiffuseMaterialOverTheSky) { check_golden("march", 12); }

}  // namespace
}  // namespace spume
