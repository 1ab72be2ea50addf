#pragma once
// Two-way rigid-fluid coupling after [AIA12] (Akinci et al. 2012, see solver.h): whatever the fluid
// does to its particles through a body's boundary particles, the body gets back with the opposite
// sign, so momentum is exchanged exactly.
//  - Pressure: a solve changes v_i by -dt_s K_i V_b grad W_ib per boundary neighbour b (pressure.h;
//    K_i = the total pressure of the solve, dt_s its step), so b receives the impulse
//    m_i dt_s K_i V_b grad W_ib, m_i = rho0 (2r)^3.
//  - Viscosity: the boundary friction term a_ib of forces.cpp acts on the fluid for the step, so b
//    receives the force -m_i a_ib.
// Torques are about the body's centre, with each boundary particle's lever arm at the current pose.
// Sums run over fixed chunks of fluid particles in index order, then over chunks in order, so the
// result is the same for any thread count.
#include <vector>

#include "sim/core/vec.h"
#include "sim/fluid/boundary.h"
#include "sim/fluid/boundary_pressure.h"
#include "sim/fluid/fluid_params.h"
#include "sim/fluid/neighbours.h"
#include "sim/fluid/particles.h"

namespace spume::fluid {

struct BodyLoads {
  std::vector<Vec3d> impulse, angular_impulse;  // N s, N m s
  std::vector<Vec3d> force, torque;             // N, N m

  void reset(size_t bodies);
  // The constant force and torque that deliver everything gathered over a step of dt (s).
  void totals(double dt, std::vector<Vec3d>& f, std::vector<Vec3d>& t) const;
};

// body[s]: body index of solid s or -1; centre[k]: body k's centre, m.
struct CouplingBodies {
  std::vector<int> body_of_solid;
  std::vector<Vec3f> centre;
};

// Adds the impulse of a pressure solve whose total pressures are p.source (m^2/s^2), with step dt_s;
// with `walls`, each pair's pressure is k_i + k_b as the solve applied it (boundary_pressure.h).
void add_pressure_impulse(const Neighbourhoods& nb, const Boundary& boundary, const WallPressure* walls,
                          const CouplingBodies& bodies, float particle_mass, double dt_s, const Particles& p,
                          BodyLoads& loads);

// Adds the boundary viscosity force at the current velocities (call before the pressure solves
// change them; the same term as forces.cpp).
void add_viscous_force(const FluidSolverParams& params, const Neighbourhoods& nb, const Boundary& boundary,
                       const CouplingBodies& bodies, float particle_mass, float h, const Particles& p,
                       BodyLoads& loads);

}  // namespace spume::fluid
