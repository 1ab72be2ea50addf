#pragma once
// How much memory a solver scene needs, known before anything is allocated, so that a scene that
// cannot fit is refused at once with the numbers instead of running into std::bad_alloc.
//
// Particle counts come from the same lattices the solver fills (fluid: every lattice point of every
// block, before those inside solids are left out, so an upper bound; boundary: exact). Bytes per
// particle were measured as the peak resident memory of `spume simulate` on the dam break at three
// sizes (see kBytesPerFluidParticle): the particle arrays, the neighbour grid, the cached neighbour
// pairs (about 30 fluid pairs of 16 bytes a particle, held twice while they are gathered) and the
// frame written to the cache.
#include <cstdint>
#include <optional>
#include <vector>

#include "fluid/fluid_params.h"
#include "scene/solids.h"

namespace spume::fluid {

struct MemoryEstimate {
  double fluid_particles = 0.0;     // upper bound
  double boundary_particles = 0.0;  // exact
  double bytes = 0.0;
};

constexpr double kBytesPerFluidParticle = 1400.0;
constexpr double kBytesPerBoundaryParticle = 120.0;
constexpr double kFixedBytes = 64.0e6;  // the neighbour grids' cell tables (at least 4M cells each)

MemoryEstimate estimate_memory(const FluidSolverParams& params, const std::vector<FluidBlock>& blocks,
                               const SolidSet& solids);

// The memory the kernel could give this process now: /proc/meminfo's MemAvailable, lowered to the
// room left under a cgroup v2 limit (memory.max - memory.current) when there is one. nullopt where
// neither can be read.
std::optional<double> available_memory_bytes();

// Throws Error with the counts, the estimate and the available memory when the estimate exceeds it.
void check_memory(const MemoryEstimate& estimate, std::optional<double> available);

}  // namespace spume::fluid
