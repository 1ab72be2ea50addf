#pragma once
// The fluid particles as parallel arrays (structure of arrays), and how they are created and reordered.
#include <cstdint>
#include <span>
#include <vector>

#include "sim/core/vec.h"
#include "sim/fluid/fluid_params.h"
#include "sim/fluid/lanes.h"
#include "sim/geometry/solids.h"

namespace spume::fluid {

struct Particles {
  // State carried from step to step (reordered with the particles).
  std::vector<Vec3f> x;               // m
  std::vector<Vec3f> v;               // m/s
  std::vector<uint32_t> id;           // stable ids 0..n-1
  std::vector<float> density_warm;    // accumulated density-solve pressure * dt^2 (warm start)
  std::vector<float> divergence_warm; // accumulated divergence-solve pressure * dt (warm start)
  // Per-step quantities (recomputed each step, not reordered).
  std::vector<float> density;         // rho / rho0 (dimensionless)
  std::vector<float> factor;          // DFSPH factor alpha_i of [BK17] / rho_i, in rho0 units, m^2
  std::vector<Vec3f> accel;           // non-pressure acceleration, m/s^2
  std::vector<float> pressure;        // Jacobi pressure increment k_i = rho0 p_i / rho_i^2, m^2/s^2
  std::vector<float> source;          // pressure applied so far in the current solve, m^2/s^2
  std::vector<Padded3> x4, v4;        // x and v padded to 4 floats during a pressure solve (lanes.h)

  size_t size() const { return x.size(); }
  void resize(size_t n);
  // Reorders the carried state so that new index k holds old index order[k].
  void reorder(std::span<const uint32_t> order);
};

// The lattice of spacing 2r centred in a block: n[a] points from start[a] along each axis (n may be 0).
struct BlockLattice {
  double n[3] = {0, 0, 0};
  double start[3] = {0, 0, 0};  // m, the first point's coordinates
  double count() const { return n[0] * n[1] * n[2]; }
};
BlockLattice block_lattice(const FluidBlock& block, float radius);

// Fills the blocks on lattices of spacing 2r centred in each block, in block order, then z, y, x
// (x fastest); ids follow that order. Lattice points inside `solids`, or within `clearance` (m) of
// a box or sphere, are skipped and counted.
Particles fill_blocks(const std::vector<FluidBlock>& blocks, float radius, const SolidSet& solids, float clearance,
                      size_t& skipped);

}  // namespace spume::fluid
