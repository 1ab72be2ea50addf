#pragma once
// Formation potentials of every fluid particle (MODEL.md §1): trapped air (Eq. 2), wave crest
// (Eqs. 4-7) and kinetic energy, each clamped and scaled to [0, 1] by Eq. 1.
#include <span>
#include <vector>

#include "sim/diffuse/fluid_state.h"
#include "sim/diffuse/params.h"
#include "sim/grid/neighbour_grid.h"
#include "sim/geometry/solids.h"

namespace spume {

struct FormationPotentials {
  // Indexed like the fluid state (original particle order).
  std::vector<Vec3f> normals;      // unit outward surface normal, zero for interior particles
  std::vector<float> trapped_air;  // I_ta
  std::vector<float> wave_crest;   // I_wc
  std::vector<float> kinetic;      // I_k

  // Working buffers kept between steps (in grid order), so that a step touches no fresh memory.
  std::vector<Vec3f> sorted_velocity, sorted_normal;
};

// Surface normals from the colour-field gradient: grad c_i = sum_j V W'(r_ij) x_ij / r_ij with the
// cubic spline of support h and the uniform particle volume V = (2r)^3; n_i = -grad c_i / |grad c_i|
// for surface particles (|grad c_i| h >= surface_threshold and fewer than surface_neighbour_fraction
// of a full neighbourhood within h), else zero: inside, the direction is noise (MODEL.md §8.10).
// `grid` must be built over state.positions with support radius h.
// `solids` (may be null) cut the neighbourhood: next to a wet wall the count and the gradient include
// the water the wall stands for (geometry/solid_coverage.h), so the layer against a wall is interior.
void compute_normals(const NeighbourGrid& grid, float particle_volume, const DiffuseParams& params,
                     const SolidSet* solids, std::vector<Vec3f>& normals);

// Eq. 5's curvature sum of sorted particle si with unit normal ni: Eqs. 4 and 6 over the surface
// particles (those with a normal) within `radius` (at most twice the grid's support), weighted by
// Eq. 3 at that radius. The radius is diffuse.crest_support h, 2 h by default (MODEL.md §8.10).
float crest_curvature(const NeighbourGrid& grid, std::span<const Vec3f> sorted_normal, uint32_t si, const Vec3f& ni,
                      float radius);

// Particles with I_k = 0 get I_ta = I_wc = 0 without their neighbour sums: Eq. 8 multiplies by I_k.
void compute_potentials(const NeighbourGrid& grid, const FluidStepState& state, const DiffuseParams& params,
                        float particle_volume, const SolidSet* solids, FormationPotentials& out);

}  // namespace spume
