#include "sim/io/stored_mass_check.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/core/error.h"
#include "sim/core/unusable_masses.h"

namespace spume {

namespace {
constexpr double kMaxMassRatio = 2.0;
}  // namespace

StoredMassCheck check_stored_masses(const FluidFrame& frame, const std::string& file, float radius,
                                    float rest_density) {
  StoredMassCheck check;
  if (frame.masses.empty() || !(radius > 0.0f) || !(rest_density > 0.0f)) return check;
  const double volume = std::pow(2.0 * double(radius), 3.0);
  const double implied = double(rest_density) * volume;
  // Masses of 0 or less say "no mass" (Houdini's -1): the run weighs each with the implied mass and says
  // so; the median is of the others.
  std::vector<float> masses;
  for (const float m : frame.masses)
    if (usable_mass(m)) masses.push_back(m);
  if (masses.empty()) {
    const UnusableMasses odd = unusable_masses(frame.masses);
    check.use_stored = false;
    check.note = str("warning: ", file, ": ", odd.describe(frame.masses.size()), ", so none weighs a particle (Houdini "
                     "writes -1 where no mass was set): every particle weighs rho0 (2r)^3 = ", implied, " kg");
    return check;
  }
  std::nth_element(masses.begin(), masses.begin() + std::ptrdiff_t(masses.size() / 2), masses.end());
  const double stored = double(masses[masses.size() / 2]);
  const double ratio = stored / implied;
  if (ratio >= 1.0 / kMaxMassRatio && ratio <= kMaxMassRatio) return check;
  check.use_stored = false;
  check.note = str("warning: ", file, ": the particles' stored mass (median ", stored, " kg) is ", ratio,
                   " times the mass fluid.rest_density and fluid.radius imply, rho0 (2r)^3 = ", rest_density, " x (2 x ",
                   radius, ")^3 = ", implied, " kg: used as stored, every kinetic score (E_k, Eqs. 2 and 7) would be ",
                   ratio, " times too ", ratio > 1.0 ? "large" : "small", ". The stored masses are not used; every "
                   "particle weighs ", implied, " kg. If they are right, set fluid.rest_density = ",
                   stored / volume, " (their median over (2r)^3) and they are used");
  return check;
}

}  // namespace spume
