#pragma once
// What each diffuse particle needs from the fluid around it, in one pass: the fluid-neighbour count
// within h (classification, MODEL.md §3) and the kernel-averaged fluid velocity (advection, §4).
//
// The velocity average uses the poly6 kernel shape (Mueller et al. 2003): MODEL.md §4 asks for any
// normalised symmetric kernel, the normalisation cancels in the ratio, and poly6 needs no square root.
// Diffuse particles are sorted by half-cell of the fluid grid and processed in groups of one
// half-cell: each grid cell's 3x3x3 block of fluid particles is gathered once into contiguous arrays,
// each group keeps only the part of it within h of the group's bounding box (about half), and every
// particle of the group scans that.
#include <span>
#include <vector>

#include "sim/grid/neighbour_grid.h"
#include "sim/core/radix_sort.h"

namespace spume {

// sample_fluid writes the first three arrays whole at every call, so between calls their buffers may
// be lent (the simulator's compaction does).
struct FluidSamples {
  std::vector<float> neighbour_count;  // fluid particles within h (before any solid share)
  std::vector<Vec3f> fluid_velocity;   // sum_f v_f K / sum_f K; zero where the sum of K is zero
  std::vector<float> kernel_sum;       // sum_f K with K = (1 - r^2/h^2)^3 unnormalised; zero: no fluid within h
  std::vector<uint32_t> cell_order;    // diffuse indices sorted by (half-)cell: a spatially coherent order

  // Working buffers kept between calls, so that a step touches no fresh memory.
  std::vector<uint32_t> group_start;
  RadixSorter sorter;

  size_t bytes() const;  // what all of the above hold
};

// `sorted_motion[j]` is the advecting velocity of the grid's j-th sorted fluid particle.
void sample_fluid(const NeighbourGrid& grid, std::span<const Vec3f> sorted_motion, std::span<const Vec3f> positions,
                  FluidSamples& out);

}  // namespace spume
