#pragma once
// A cache's stored particle masses against the mass its radius and rest density imply, rho0 (2r)^3.
// E_k (Eqs. 2 and 7) grows with the mass, so a placeholder mass (1 kg is a common default of particle
// tools) makes every kinetic score, and so the trapped-air and wave-crest emission, that many times
// too large, and nothing else shows it.
#include <string>

#include "sim/core/frames.h"

namespace spume {

struct StoredMassCheck {
  bool use_stored = true;  // false: the masses are far from rho0 (2r)^3 and the implied mass is used
  std::string note;        // for the log ("" when there are no masses or they agree)
};

// The median of `frame`'s masses (read from `file`; those of 0 or less, Houdini's "not set", left out:
// the run weighs them with the implied mass) against rest_density (2 radius)^3: within a
// factor 2 they are used (SPH codes give a particle 0.8 to 1 times that volume); beyond, a warning
// with both numbers, the implied mass is used, and the message names fluid.rest_density, whose value
// their median implies, for masses that are right. When no mass is > 0, none is used.
StoredMassCheck check_stored_masses(const FluidFrame& frame, const std::string& file, float radius,
                                    float rest_density);

}  // namespace spume
