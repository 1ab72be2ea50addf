// Given tanks must hold the fluid (scene/tank_fit.h): counted on hand-built frames, where the
// particles outside are known by construction.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/container_sequences.h"
#include "sim/core/error.h"
#include "sim/scene/tank_fit.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::kSeqRadius;

class TankFit : public ::testing::Test {
 protected:

  // The collapsing column's frames (with `extra` added to the last one), surveyed.
  FluidSurvey survey(const std::vector<Vec3f>& extra = {}) {
    std::vector<std::vector<Vec3f>> frames = testing::collapsing_column();
    frames.back().insert(frames.back().end(), extra.begin(), extra.end());
    const std::string pattern = testing::write_sequence(dir, frames);
    std::vector<int> numbers;
    for (size_t k = 0; k < frames.size(); ++k) numbers.push_back(1 + int(k));
    return survey_fluid_files(pattern, numbers, "", true);
  }
  static SolidSet tank(const Vec3f& min, const Vec3f& max) {
    Solid t;
    t.kind = Solid::Kind::Tank;
    t.min = min;
    t.max = max;
    return SolidSet({t});
  }

  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

TEST_F(TankFit, TheTankTheFluidWasMadeInHoldsIt) {
  EXPECT_EQ(check_tanks_hold_fluid(survey(), tank(testing::kColumnTankMin, testing::kColumnTankMax), kSeqRadius), "");
  // Above the open top is inside: a tank lower than the fluid's top still holds it.
  EXPECT_EQ(check_tanks_hold_fluid(survey(), tank(Vec3f::Zero(), Vec3f(0.6f, 0.1f, 0.1f)), kSeqRadius), "");
  EXPECT_EQ(check_tanks_hold_fluid(survey(), SolidSet(), kSeqRadius), "");
}

TEST_F(TankFit, ATankAwayFromTheFluidIsAnErrorSayingHowMuchLiesOutside) {
  try {
    check_tanks_hold_fluid(survey(), tank(Vec3f(10, 10, 10), Vec3f(11, 11, 11)), kSeqRadius);
    FAIL() << "no error";
  } catch (const Error& e) {
    // Frame 1: 10 x 20 x 5 cells, every one outside.
    EXPECT_NE(std::string(e.what()).find("the tank [10, 10, 10] - [11, 11, 11] m does not hold the fluid: in frame 1, "
                                         "1000 of its 1000 particles (100%) lie more than 2r = 0.02 m outside"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(TankFit, ATankOneLayerTooNarrowIsAnError) {
  // The +x wall at 0.56 instead of 0.6: the last cell column (centres at 0.59) lies 0.03 m beyond it,
  // more than 2r; the one before (0.57) lies within. It is reached in frame 8: 1 of 30 columns, 3.3%.
  try {
    check_tanks_hold_fluid(survey(), tank(Vec3f::Zero(), Vec3f(0.56f, 1.0f, 0.1f)), kSeqRadius);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("in frame 8, 65 of its 1950 particles (3%)"), std::string::npos) << e.what();
  }
}

TEST_F(TankFit, AFewLeakedParticlesAreAWarningWithTheirCount) {
  // Five particles 0.1 m below the floor in the last frame (5 of 30 x 5 x 5 + 5 = 755: 0.7%).
  std::vector<Vec3f> leaked;
  for (int i = 0; i < 5; ++i) leaked.emplace_back(0.1f + 0.05f * float(i), -0.1f, 0.05f);
  const std::string warning = check_tanks_hold_fluid(survey(leaked), tank(testing::kColumnTankMin, testing::kColumnTankMax),
                                                     kSeqRadius);
  EXPECT_NE(warning.find("in frame 16, 5 of 755 fluid particles lie more than 2r = 0.02 m outside its walls"),
            std::string::npos)
      << warning;
}

}  // namespace
}  // namespace spume
