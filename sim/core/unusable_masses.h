#pragma once
// Masses a fluid file holds that cannot weigh a particle's kinetic energy (E_k = m v^2 / 2): zero or
// negative (Houdini writes -1 where no mass was set; a non-finite mass is refused as the file is read).
// Reading keeps them as the file holds them, so `info` shows them; the diffuse simulation gives such
// particles the uniform mass rho0 (2r)^3 and says so.
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace spume {

inline bool usable_mass(float m) { return std::isfinite(m) && m > 0.0f; }

struct UnusableMasses {
  size_t count = 0;            // masses that are not usable_mass
  float lo = 0.0f, hi = 0.0f;  // their range
  // "2500 of 2613 masses are not > 0 (-1 kg)"; "" when count is 0.
  std::string describe(size_t masses) const;
};

UnusableMasses unusable_masses(const std::vector<float>& masses);

}  // namespace spume
