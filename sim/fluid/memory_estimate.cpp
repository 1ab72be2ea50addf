#include "sim/fluid/memory_estimate.h"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "sim/core/error.h"
#include "sim/fluid/boundary.h"
#include "sim/fluid/particles.h"
#include "sim/keys/scene_keys.h"

namespace spume::fluid {
namespace {

std::string gigabytes(double bytes) {
  std::ostringstream out;
  out.precision(bytes < 1e10 ? 2 : 3);
  out << bytes / 1e9 << " GB";
  return out.str();
}

std::string count(double n) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, n < 1e12 ? "%.0f" : "%.3g", n);
  return buffer;
}

}  // namespace

MemoryEstimate estimate_memory(const FluidSolverParams& params, const std::vector<FluidBlock>& blocks,
                               const SolidSet& solids) {
  MemoryEstimate e;
  for (const FluidBlock& b : blocks) e.fluid_particles += block_lattice(b, params.particle_radius).count();
  e.boundary_particles = count_boundary(solids, params.boundary_spacing * params.particle_radius,
                                        keys::fluid::support_radius_of(params.particle_radius));
  e.bytes = kBytesPerFluidParticle * e.fluid_particles + kBytesPerBoundaryParticle * e.boundary_particles;
  return e;
}

void check_memory(const MemoryEstimate& e, std::optional<double> available) {
  if (!available || e.bytes <= *available) return;
  fail("fluid solver: the scene needs about ", gigabytes(e.bytes), " of memory (", count(e.fluid_particles),
       " fluid particles at about ", kBytesPerFluidParticle, " bytes each, ", count(e.boundary_particles),
       " boundary particles at about ", kBytesPerBoundaryParticle, " bytes each), but only ", gigabytes(*available),
       " is available; make fluid.radius larger (the count grows as 1 / radius^3) or the fluid blocks smaller");
}

}  // namespace spume::fluid
