#pragma once
// The two pressure solves of DFSPH [BK15, BK17: Bender & Koschier, "Divergence-free smoothed particle
// hydrodynamics", SCA 2015; "Divergence-free SPH for incompressible and viscous fluids", TVCG 2017].
//
// Both are Jacobi iterations on a per-particle pressure k_i = rho0 p_i / rho_i^2 (~ p_i / rho0, m^2/s^2) that
// changes velocities by ([BK17]; the boundary term is [AIA12]'s, with the fluid particle's pressure)
//   v_i -= dt * ( sum_j (k_i + k_j) V_j grad W_ij + k_i sum_b V_b grad W_ib ),
// and each iteration sets k_i so that particle i alone would cancel its residual:
//   divergence-free: k_i = (D rho_i / Dt / rho0) alpha_i / dt
//   constant density: k_i = (rho*_i / rho0 - 1) alpha_i / dt^2
// with rho*_i = rho_i + dt D rho_i / Dt the density predicted from the current velocities.
// Only compression is corrected (negative residuals count as 0: a free surface may expand).
//
// The wall term carries k_i once, as in [AIA12]: it is the force whose work is the change of the
// fluid particle's own pressure energy (walls store none), so walls neither gain nor give energy.
// Mirroring the pressure into the wall (k_b = k_i, twice the force) balances a resting column more
// exactly (the column then does not settle), but measured here it kept feeding energy into a tank at
// rest (rms speed 0.07 -> 0.11 m/s over 1 s, where the single factor decays to 0.017), so it is not
// used.
//
// Warm start ([BK17]; optional, off by default): each solve first applies half the previous
// step's total pressure where the fluid is compressed now. It saves about half the iterations in
// deep water, but measured here it keeps feeding energy into a tank at rest: pressure re-applied
// where the fluid no longer needs it expands the fluid, and residual clamping cannot take that back
// (rms speed 3-13 cm/s after 2 s at 4000 particles, against 0.8 cm/s without; variants that also
// let iterations lower the pressure needed relaxation and were no cheaper, or diverged).
#include "sim/fluid/boundary.h"
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
                             double dt, Particles& p);

// Corrects the predicted velocities so the density after advecting by dt is rho0.
SolveResult density_solve(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                          double dt, Particles& p);

}  // namespace spume::fluid
