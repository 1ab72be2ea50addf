#pragma once
// How much memory a solver scene needs, known before anything is allocated, so that a scene that
// cannot fit is refused at once with the numbers instead of running into std::bad_alloc.
//
// Particle counts come from the same lattices the solver fills (fluid: every lattice point of every
// block, before those inside solids are left out, so an upper bound; boundary: exact). Bytes per
// particle are measured: the peak resident memory of the fluid stage (run_fluid_stage, less the
// process before it) on scenes/dambreak.json. Over its first 4 frames, 28.9k, 84.2k and 211k fluid
// particles with 32.8k, 66.0k and 122k boundary particles, and 28.9k with 317k (a larger tank), fit
// 1.6 kB per fluid and 75 bytes per boundary particle with no constant term; over the whole run
// (91 frames: the splash spreads the fluid over more grid cells and neighbour buffers grow) the peak
// is 2.19 kB (28.9k) and 2.24 kB (84.2k) per fluid particle. Most of it was the cached neighbour
// pairs (then 16 bytes each, ~30 per particle, gathered in per-task buffers and then copied: twice,
// plus the buffers' growth slack); the particle arrays are 64 bytes (96 with the solves' padded
// copies of x and v). Fluid pairs are 8 bytes since: the 633k dam break's whole process peaked at
// 465 MB against 750 MB before (0.73 kB a particle); the constant is kept as a safe upper bound.
#include <cstdint>
#include <optional>
#include <vector>

#include "sim/core/memory_room.h"
#include "sim/fluid/fluid_params.h"
#include "sim/geometry/solids.h"

namespace spume::fluid {

struct MemoryEstimate {
  double fluid_particles = 0.0;     // upper bound
  double boundary_particles = 0.0;  // exact
  double bytes = 0.0;
};

// The measured peaks above, rounded up.
constexpr double kBytesPerFluidParticle = 2300.0;
constexpr double kBytesPerBoundaryParticle = 80.0;

MemoryEstimate estimate_memory(const FluidSolverParams& params, const std::vector<FluidBlock>& blocks,
                               const SolidSet& solids);

// Throws Error with the counts, the estimate and the available memory when the estimate exceeds it.
void check_memory(const MemoryEstimate& estimate, std::optional<double> available);

}  // namespace spume::fluid
