#pragma once
// Solid boundaries as particles: layers of "frozen fluid" inside each solid, down to the depth h
// below its surface, each particle standing for the solid volume V_b of its lattice cell (or shell
// segment). A fluid particle's density then gets + rho0 V_b W_ib, and pressure pushes it from the wall
// (with the particle's own pressure, [AIA12], or the fluid's extrapolated into the wall: pressure.h).
//
// Why not the single surface layer of Akinci et al. 2012 (V_b = 1 / sum_k W_bk)? Summed over a plane,
// that layer contributes W1(y) / W1(0) to a fluid particle at distance y (W1 = the kernel integrated
// over the plane), i.e. 1 at the wall and ~0.7 at y = r, where the missing half space of fluid is worth
// 0.5 and ~0.15. Measured here: a tank at rest started at mean rho/rho0 = 1.18, 1.82 at its corners, so
// the fluid pulls away from the walls by about a particle and the centre of mass jumps. Layers that
// continue the fluid lattice (spacing 2r, walls halfway between lattice planes, V_b = (2r)^3) give
// rho/rho0 = 1.0000 at the wall (lattice sum 0.99997) and need no tuning factor. They cost fewer
// particles than a surface layer at spacing r (2 layers at 2r vs 1 at r), handle corners by
// construction, and move rigidly with kinematic solids (V_b stays constant).
//
// Weakness shared with Akinci's layer: a lone particle (spray, a thin film) has too little density
// for any pressure, so walls do not repel it until it touches them; the solver projects the few that
// cross a surface back out (SolverStats::corrections, ~0.01-0.05% of particle-steps in splashing
// scenes). Thin boxes (< 2L layers) are weaker walls and rely more on that projection.
//
// Geometry: tanks get L layers outside every wall (their open top excepted); boxes get L layers
// inside their faces (all of it when thinner than 2L layers); spheres get L concentric Fibonacci
// shells. L = number of layers within h of the surface (2 at the default spacing 2r). Rotated boxes
// are sampled in their own frame and turned about their centre. Dynamic bodies keep their particles
// in the body frame (relative to the centre) and move with the body's full rigid transform.
#include <cstdint>
#include <vector>

#include "sim/core/vec.h"
#include "sim/grid/neighbour_grid.h"
#include "sim/geometry/solids.h"

namespace spume::fluid {

struct Boundary {
  // Per particle, in sampling order.
  std::vector<Vec3f> rest;      // position with the solid at zero offset (bodies: in the body frame), m
  std::vector<uint32_t> solid;  // index into the solid set
  std::vector<float> volume;    // V_b, m^3
  // The grid over the current positions, and per-particle data in the grid's sorted order.
  NeighbourGrid grid;
  std::vector<float> sorted_volume;
  std::vector<Vec3f> sorted_velocity;  // m/s
  std::vector<uint32_t> sorted_solid;  // index into the solid set
  std::vector<uint8_t> sorted_on_body; // 1 where the particle belongs to a dynamic body
  bool any_moving = false;
  float h = 0.0f;  // kernel support, m

  size_t size() const { return rest.size(); }
};

// Where one solid's particles are: x = rest + translation, or for a dynamic body (rest in its frame)
// x = rotation rest + translation, moving at velocity + angular_velocity x (x - translation).
struct SolidPlacement {
  Vec3f translation = Vec3f::Zero();                      // m
  Eigen::Matrix3f rotation = Eigen::Matrix3f::Identity(); // bodies only
  bool body = false;
  Vec3f velocity = Vec3f::Zero();                         // m/s
  Vec3f angular_velocity = Vec3f::Zero();                 // rad/s, bodies only
};

// Samples every solid at `spacing` (m, adjusted per axis to fit the solid exactly) within depth h.
Boundary sample_boundary(const SolidSet& solids, float spacing, float h);

// The number of particles sample_boundary makes (exact, without making them; as a double so that
// absurd solids are counted rather than overflowed).
double count_boundary(const SolidSet& solids, float spacing, float h);

// Places the particles (one placement per solid; a no-op after the first call when nothing moves:
// static walls keep their grid, volumes and zero velocities) and sets their velocities.
void place_boundary(Boundary& b, const std::vector<SolidPlacement>& placements, bool first);

// Sets only the velocities (the wall speed during a step of the pressure solve), at the current
// positions.
void set_boundary_velocity(Boundary& b, const std::vector<SolidPlacement>& placements);

// Layers of a box lattice (cells of about `spacing`, centres at lo + (i + 1/2) s), with the volume of
// one cell. Tank: the `layers` cells outside [lo, hi] (none above hi along open_axis if >= 0);
// Box: the cells inside within `layers` of a face.
void sample_tank_walls(const Vec3f& lo, const Vec3f& hi, float spacing, int layers, int open_axis,
                       std::vector<Vec3f>& out, float& cell_volume);
void sample_box_layers(const Vec3f& lo, const Vec3f& hi, float spacing, int layers, std::vector<Vec3f>& out,
                       float& cell_volume);
// Concentric shells at depths (k + 1/2) spacing, each a Fibonacci lattice, with each point's share of
// its shell's volume.
void sample_sphere_layers(const Vec3f& c, float radius, float spacing, int layers, std::vector<Vec3f>& out,
                          std::vector<float>& volume);

}  // namespace spume::fluid
