// Stored masses against rho0 (2r)^3 (io/stored_mass_check.h): at r = 0.02 m and rho0 = 1000 kg/m^3 the
// implied mass is 1000 x 0.04^3 = 0.064 kg, worked by hand.
#include <gtest/gtest.h>

#include "sim/io/stored_mass_check.h"

namespace spume {
namespace {

FluidFrame with_masses(std::vector<float> masses) {
  FluidFrame f;
  f.positions.assign(masses.size(), Vec3f::Zero());
  f.masses = std::move(masses);
  return f;
}

TEST(StoredMassCheck, APlaceholderMassIsNotUsedAndBothNumbersAreSaid) {
  const StoredMassCheck c = check_stored_masses(with_masses({1, 1, 1, 1}), "f_1.ply", 0.02f, 1000.0f);
  EXPECT_FALSE(c.use_stored);
  EXPECT_EQ(c.note.rfind("warning: f_1.ply: the particles' stored mass (median 1 kg) is 15.625 times", 0), 0u) << c.note;
  EXPECT_NE(c.note.find("= 0.064 kg"), std::string::npos) << c.note;
  EXPECT_NE(c.note.find("15.625 times too large"), std::string::npos) << c.note;
  EXPECT_NE(c.note.find("set fluid.rest_density = 15625"), std::string::npos) << c.note;  // 1 / 0.04^3
  // A hundredth of it: too small, 0.15625 times.
  const StoredMassCheck light = check_stored_masses(with_masses({0.01f, 0.01f, 0.01f}), "f", 0.02f, 1000.0f);
  EXPECT_FALSE(light.use_stored);
  EXPECT_NE(light.note.find("0.15625 times too small"), std::string::npos) << light.note;
}

TEST(StoredMassCheck, MassesNearTheImpliedOneAreUsedSilently) {
  // SPlisHSPlasH gives a particle 0.8 (2r)^3: 0.0512 kg; one odd particle does not move the median.
  const StoredMassCheck c = check_stored_masses(with_masses({0.0512f, 0.0512f, 5.0f}), "f", 0.02f, 1000.0f);
  EXPECT_TRUE(c.use_stored);
  EXPECT_EQ(c.note, "");
  // The same masses at a rest density that implies them: 1 kg at 15625 kg/m^3.
  EXPECT_TRUE(check_stored_masses(with_masses({1, 1}), "f", 0.02f, 15625.0f).use_stored);
  // No masses: nothing to check.
  EXPECT_TRUE(check_stored_masses(with_masses({}), "f", 0.02f, 1000.0f).use_stored);
}

// Houdini's -1 ("no mass set") is no mass: with some usable masses the median is theirs, and the run
// weighs the -1 particles with the implied mass; with none, no stored mass is used. No advice to set a
// negative rest density (-1 kg over 0.04^3 m^3 would be -15625).
TEST(StoredMassCheck, MassesOfMinusOneAreNoMassesAndNeverNegativeAdvice) {
  const StoredMassCheck some = check_stored_masses(with_masses({-1, -1, 0.064f}), "f", 0.02f, 1000.0f);
  EXPECT_TRUE(some.use_stored);
  EXPECT_EQ(some.note, "");
  const StoredMassCheck none = check_stored_masses(with_masses({-1, -1, -1}), "f", 0.02f, 1000.0f);
  EXPECT_FALSE(none.use_stored);
  EXPECT_NE(none.note.find("3 of 3 masses are not > 0 (-1 kg)"), std::string::npos) << none.note;
  EXPECT_NE(none.note.find("every particle weighs rho0 (2r)^3 = 0.064 kg"), std::string::npos) << none.note;
  EXPECT_EQ(none.note.find("rest_density = -"), std::string::npos) << none.note;
}

}  // namespace
}  // namespace spume
