// Case 16. The same water read at two frame rates makes the same diffuse material: SPlisHSPlasH's
// emitter (50 fps) read as it is and as every second frame at 25 fps emits as much by each common time,
// and holds as many spray, foam and bubble particles then. Emission (Eq. 8) is a rate times the step:
// a step of twice the length must emit twice as much.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>

#include "tests/support/csv.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::run_spume;

const fs::path kFrames = fs::path(SPUME_TEST_DATA_DIR) / "../../../shared/data/splishsplash_emitter/frames";

// Frame 2j at 50 fps and frame j at 25 fps are both at t = j / 25 s (spume's frame time: number / fps).
constexpr int kLastPair = 6;  // t up to 0.24 s

struct Row {
  double generated_so_far = 0.0;
  double spray = 0.0, foam = 0.0, bubbles = 0.0;
};

// stats.csv by frame: the emission summed up to each frame, and the counts there.
std::map<int, Row> read_stats(const fs::path& path) {
  const auto rows = testing::read_csv(path);
  std::map<int, Row> out;
  if (rows.empty()) return out;
  std::map<std::string, size_t> column;
  for (size_t c = 0; c < rows[0].size(); ++c) column[rows[0][c]] = c;
  double sum = 0.0;
  for (size_t i = 1; i < rows.size(); ++i) {
    const auto& r = rows[i];
    sum += std::stod(r[column.at("generated")]);
    out[std::stoi(r[column.at("frame")])] = {sum, std::stod(r[column.at("spray")]), std::stod(r[column.at("foam")]),
                                             std::stod(r[column.at("bubbles")])};
  }
  return out;
}

// The emitter's frames 2-12 at 50 fps against its frames 2, 4, ..., 12 at 25 fps (t = 0.04 to 0.24 s).
// Measured (2026, r = 0.015 m, default keys): the emission summed to t = 0.20 and 0.24 s is 2,871 and
// 3,709 at 50 fps; at 25 fps with 2 substeps (the same 0.02 s steps, the fluid between the frames
// interpolated) 2,869 and 3,714, with 1 substep (0.04 s steps) 2,918 and 3,776; foam and bubbles at
// t = 0.16-0.24 s lie within 3% with 2 substeps, but 17-20% apart with 1 (bubbles counted on steps twice
// as long), so the counts are held with equal steps. Earlier times hold too few particles to compare.
TEST(FrameRateInvariance, EveryOtherFrameAtHalfTheRateEmitsAndHoldsAlike) {
  if (!fs::exists(kFrames / "ParticleData_Fluid_12.bgeo")) GTEST_SKIP() << kFrames << " not present";
  testing::TempDir dir;
  fs::create_directories(dir / "fps50"), fs::create_directories(dir / "fps25");
  for (int k = 2; k <= 2 * kLastPair; ++k) {
    const fs::path source = fs::absolute(kFrames / ("ParticleData_Fluid_" + std::to_string(k) + ".bgeo"));
    fs::create_symlink(source, dir / "fps50" / ("f_" + std::to_string(k) + ".bgeo"));
    if (k % 2 == 0) fs::create_symlink(source, dir / "fps25" / ("f_" + std::to_string(k / 2) + ".bgeo"));
  }
  auto run = [&](const std::string& name, int fps, int substeps) {
    const fs::path out = dir / ("out_" + name + "_" + std::to_string(substeps));
    const CommandResult r = run_spume("simulate --fluid '" + (dir / name / "f_%d.bgeo").string() + "' --radius 0.015 --fps " +
                                      std::to_string(fps) + " --set diffuse.substeps=" + std::to_string(substeps) +
                                      " --out " + out.string());
    EXPECT_EQ(r.status, 0) << r.output;
    return read_stats(out / "f/stats.csv");
  };
  const auto at50 = run("fps50", 50, 1), at25 = run("fps25", 25, 1), at25_equal_steps = run("fps25", 25, 2);
  ASSERT_EQ(at50.size(), size_t(2 * kLastPair - 1));
  ASSERT_EQ(at25.size(), size_t(kLastPair));
  ASSERT_EQ(at25_equal_steps.size(), size_t(kLastPair));
  for (int j = 4; j <= kLastPair; ++j) {
    SCOPED_TRACE("t = " + std::to_string(j / 25.0) + " s");
    const Row& a = at50.at(2 * j);
    const Row& b = at25.at(j);
    const Row& c = at25_equal_steps.at(j);
    ASSERT_GT(a.generated_so_far, 1500.0);  // sqrt(n) / n below 2.6%
    // Emission is a rate times the step: the same by each time whatever the frame interval.
    if (j >= 5) {
      EXPECT_NEAR(c.generated_so_far / a.generated_so_far, 1.0, 0.005) << c.generated_so_far << " vs " << a.generated_so_far;
      EXPECT_NEAR(b.generated_so_far / a.generated_so_far, 1.0, 0.03) << b.generated_so_far << " vs " << a.generated_so_far;
    }
    for (const auto& [type, x, y] : {std::tuple{"foam", a.foam, c.foam}, std::tuple{"bubbles", a.bubbles, c.bubbles}}) {
      ASSERT_GT(x, 500.0) << type;
      EXPECT_NEAR(y / x, 1.0, 0.10) << type << ": " << y << " vs " << x;
    }
  }
}

}  // namespace
}  // namespace spume
