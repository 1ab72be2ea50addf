#include "sim/core/unusable_masses.h"

#include <algorithm>

#include "sim/core/error.h"

namespace spume {

std::string UnusableMasses::describe(size_t masses) const {
  if (count == 0) return "";
  return str(count, " of ", masses, count == 1 ? " masses is" : " masses are", " not > 0 (",
             lo == hi ? str(lo) : str(lo, " .. ", hi), " kg)");
}

UnusableMasses unusable_masses(const std::vector<float>& masses) {
  UnusableMasses u;
  for (const float m : masses) {
    if (usable_mass(m)) continue;
    u.lo = u.count == 0 ? m : std::min(u.lo, m);
    u.hi = u.count == 0 ? m : std::max(u.hi, m);
    ++u.count;
  }
  return u;
}

}  // namespace spume
