#pragma once
// Per-step neighbourhoods of the fluid particles, cached as pair lists so the pressure iterations
// stream through memory instead of re-querying the grid, plus the kernel sums that depend only on
// positions: density and the DFSPH factor.
//
// Units: densities are ratios rho / rho0 and particles carry volumes (fluid V = (2r)^3, boundary V_b),
// so "mass" m_j reads rho0 V_j and rho0 cancels from every solver equation.
#include <cstdint>
#include <vector>

#include "sim/core/cubic_spline.h"
#include "sim/core/vec.h"
#include "sim/fluid/boundary.h"
#include "sim/fluid/particles.h"
#include "sim/grid/neighbour_grid.h"

namespace spume::fluid {

// A boundary neighbour j of particle i with the volume-weighted kernel gradient g = V_b grad_i W_ib
// (1/m). Storing g (16 bytes a pair) lets the rarer boundary loops skip gathering the boundary
// particle's position.
struct Pair {
  uint32_t j;
  float gx, gy, gz;
  Vec3f g() const { return Vec3f(gx, gy, gz); }
};

// A fluid neighbour j of particle i with s = V grad_factor(|x_i - x_j|), so that the volume-weighted
// kernel gradient is V grad_i W_ij = s (x_i - x_j) (1/m), computed by the same float operations as
// when the pair was found, hence the same bits. 8 bytes a pair instead of 16 with g stored: the pressure
// iterations stream this list about 10 times a step (once an iteration: fused_sweep.h), and x_j is
// gathered anyway and mostly sits in cache, neighbours of consecutive particles overlapping.
struct FluidPair {
  uint32_t j;
  float s;
  Vec3f g(const Vec3f& xij) const { return s * xij; }  // xij = x_i - x_j
};

struct Neighbourhoods {
  std::vector<uint32_t> offset;          // n + 1: fluid pairs of i are pairs[offset[i], offset[i+1])
  std::vector<FluidPair> pairs;          // fluid neighbours j != i within h
  std::vector<uint32_t> boundary_offset; // n + 1
  std::vector<Pair> boundary_pairs;      // boundary neighbours (index into the boundary's sorted order)
  std::vector<Vec3f> boundary_grad;      // sum_b V_b grad W_ib per particle, 1/m
  struct Reach {                         // the lowest and highest fluid index among i and its neighbours
    uint32_t lowest, highest;
  };
  std::vector<Reach> reach;
  std::vector<uint32_t> counts;          // scratch
  struct Task {                          // scratch: pairs of one fixed range of grid cells
    std::vector<FluidPair> pairs;
    std::vector<Pair> boundary_pairs;
  };
  std::vector<Task> tasks;
};

// `grid` must have been built over p.x with p already reordered into the grid's sorted order, so
// sorted index == particle index. Fills `nb`, p.density (rho/rho0) and p.factor (alpha_i).
void build_neighbourhoods(const NeighbourGrid& grid, const Boundary& boundary, const CubicSpline& kernel, float volume,
                          Particles& p, Neighbourhoods& nb);

}  // namespace spume::fluid
