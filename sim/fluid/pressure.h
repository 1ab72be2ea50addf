#pragma once
// The two pressure solves of DFSPH [BK15, BK17: Bender & Koschier, "Divergence-free smoothed particle
// hydrodynamics", SCA 2015; "Divergence-free SPH for incompressible and viscous fluids", TVCG 2017].
//
// Both are Jacobi iterations on a per-particle pressure k_i = rho0 p_i / rho_i^2 (~ p_i / rho0, m^2/s^2) that
// changes velocities by ([BK17]; the wall term is [AIA12]'s with k_b = 0, [ARH12]'s with k_b extrapolated)
//   v_i -= dt * ( sum_j (k_i + k_j) V_j grad W_ij + sum_b (k_i + k_b) V_b grad W_ib ),
// and each iteration sets k_i so that particle i alone would cancel its residual:
//   divergence-free: k_i = (D rho_i / Dt / rho0) alpha_i / dt
//   constant density: k_i = (rho*_i / rho0 - 1) alpha_i / dt^2
// with rho*_i = rho_i + dt D rho_i / Dt the density predicted from the current velocities.
// Only compression is corrected (negative residuals count as 0: a free surface may expand).
//
// The wall's pressure k_b is 0 by default, so the wall term is k_i's alone ([AIA12]), or, with
// fluid.solver.wall_pressure = extrapolated (walls != nullptr), extrapolated from the fluid beside the
// wall. The own form cannot hold deep water: with boundary layers that complete a particle's
// neighbourhood, sum_b V_b grad W_ib is about minus the fluid's sum, so a floor particle's own pressure
// cancels on itself and every other layer falls, unseen by the density residual. Why the extrapolated
// form is not the default yet: sim/MODEL.md §10; measured in tests/bench/RESULTS.md §7.
//
// Warm start ([BK17]; optional, off by default): each solve first applies half the previous
// step's total pressure where the fluid is compressed now. Off, because pressure re-applied where the
// fluid no longer needs it expands the fluid, and residual clamping cannot take that back: it feeds
// energy into a tank at rest (tests/bench/RESULTS.md §6).
#include "sim/fluid/boundary.h"
#include "sim/fluid/boundary_pressure.h"
#include "sim/fluid/fluid_params.h"
#include "sim/fluid/neighbours.h"
#include "sim/fluid/particles.h"

namespace spume::fluid {

struct SolveResult {
  int iterations = 0;  // Jacobi iterations after the warm start
  double error = 0.0;  // final average error in the solve's own measure (see FluidSolverParams)
  bool converged = true;
};

// Removes the compression rate of the current velocities (run after the neighbourhoods are built at
// the new positions). `dt` is the step the error measure refers to. Boundary velocities are the
// boundary's sorted_velocity.
SolveResult divergence_solve(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                             double dt, Particles& p, WallPressure* walls);

// Corrects the predicted velocities so the density after advecting by dt is rho0.
SolveResult density_solve(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                          double dt, Particles& p, WallPressure* walls);

}  // namespace spume::fluid
