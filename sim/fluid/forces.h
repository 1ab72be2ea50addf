#pragma once
// Non-pressure accelerations: gravity and viscosity.
//
// Viscosity is the standard SPH Laplacian of the velocity [Mon05, §6; SPlisHSPlasH calls it "Standard"]:
//   a_i = 2 (d + 2) nu sum_j (m_j / rho_j) (v_ij . x_ij) / (|x_ij|^2 + 0.01 h^2) grad W_ij,   d = 3,
// with nu the kinematic viscosity (m^2/s). It conserves momentum, damps only relative motion along
// the line between particles (no damping of rigid rotation), and is physical in its parameter, unlike
// XSPH's dimensionless smoothing. Boundary particles enter the same sum with their solid's velocity
// and nu_b (wall friction; 0 = free slip), m_j / rho_j read as V_b rho0 / rho_i.
//
// Optional XSPH smoothing [Monaghan 1989]: a_i += (xsph / dt) sum_j (m_j / rho_j) (v_j - v_i) W_ij,
// i.e. each step moves v_i the fraction xsph towards its neighbours' kernel average (dt is the
// previous step's, which the CFL condition keeps close to the current one).
//
// [Mon05] J. J. Monaghan, Smoothed particle hydrodynamics, Rep. Prog. Phys. 68 (2005) 1703-1759.
// [Monaghan 1989] On the problem of penetration in particle methods, J. Comput. Phys. 82 (1989).
#include "sim/fluid/boundary.h"
#include "sim/fluid/fluid_params.h"
#include "sim/fluid/neighbours.h"
#include "sim/fluid/particles.h"

namespace spume::fluid {

// p.accel = gravity + viscosity, from p.v and the boundary's sorted_velocity.
void non_pressure_accelerations(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                                float h, float volume, double dt, Particles& p);

}  // namespace spume::fluid
