#pragma once
// Wall pressure extrapolated from the fluid beside it ([ARH12]: Adami, Hu & Adams, "A generalized
// wall boundary condition for smoothed particle hydrodynamics", JCP 2012), for the pressure solves.
//
// Each boundary particle b within h of the fluid takes the Shepard average of its fluid neighbours'
// pressures plus the hydrostatic rise from them to b:
//   k_b = sum_f w_bf k_f + g . sum_f w_bf (x_b - x_f) (the second term in the density solve's first
//   application only: it is part of the step's total pressure, not of each increment),
// with w_bf = W_bf / sum_f W_bf; a fluid particle then feels the wall as it feels fluid,
//   sum_b (k_i + k_b) V_b grad W_ib.
// Why: with k_b = k_i (or k_i alone, [AIA12]) a wall's pressure is uniform along it, so a particle at a
// side wall gets only its fluid half's share of the vertical pressure gradient that holds it against
// gravity (a quarter in an edge), and with k_i alone a floor particle's own push cancels (pressure.h).
// A moving wall's own acceleration, which [ARH12] subtracts from g, is left out: the rise spans less
// than h, so a piston at the lighthouse's 0.7 g misses at most 0.7 g h of pressure (2 cm of water at
// r = 7.5 mm) against the ~30 cm of water at its foot.
#include <cstdint>
#include <vector>

#include "sim/core/cubic_spline.h"
#include "sim/core/vec.h"
#include "sim/fluid/boundary.h"
#include "sim/fluid/neighbours.h"
#include "sim/fluid/particles.h"

namespace spume::fluid {

struct WallPressure {
  // The boundary particles within h of some fluid particle (sorted boundary index, ascending), and
  // for each its fluid neighbours (ascending) with their Shepard weights.
  std::vector<uint32_t> sample;
  std::vector<uint32_t> offset;  // sample.size() + 1
  std::vector<uint32_t> fluid;
  std::vector<float> weight;
  std::vector<float> rise;       // per sample: g . sum_f w_bf (x_b - x_f), m^2/s^2 (> 0 below the fluid)
  std::vector<float> k;          // per boundary particle (sorted index): the current increment
  std::vector<float> total;      // per boundary particle: applied so far in the current solve
  std::vector<uint32_t> next;    // scratch for build: per boundary particle, its next slot

  // Rebuilds the lists from the neighbourhoods (after build_neighbourhoods at new positions).
  void build(const Neighbourhoods& nb, const Boundary& boundary, const CubicSpline& kernel, const Particles& p,
             const Vec3f& gravity);
  // k_b from the fluid's increments k_f (p.pressure), plus `rise_scale` times the hydrostatic rise,
  // so that each wall particle's total over the solve stays >= 0.
  void extrapolate(const std::vector<float>& fluid_k, float rise_scale);
};

}  // namespace spume::fluid
