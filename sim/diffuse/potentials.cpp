#include "sim/diffuse/potentials.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/core/cubic_spline.h"
#include "sim/core/parallel.h"
#include "sim/core/target_clones.h"
#include "sim/diffuse/kernels.h"
#include "sim/grid/block_buffer.h"
#include "sim/geometry/solid_coverage.h"

namespace spume {
namespace {

// Runs fn(cell_begin, cell_end, block) for every occupied cell, in parallel; the block holds the
// cell's 3x3x3 neighbourhood with the given per-point attributes.
template <typename Fn>
void for_each_cell_block(const NeighbourGrid& grid, std::initializer_list<std::span<const Vec3f>> attributes, Fn&& fn) {
  parallel_for(grid.occupied_cell_count(), 16, [&](size_t cb, size_t ce) {
    BlockBuffer block;
    for (size_t c = cb; c < ce; ++c) {
      block.gather(grid, grid.occupied_key(c), attributes);
      fn(grid.cell_begin(c), grid.cell_begin(c + 1), block);
    }
  });
}

// Eq. 2's sum over the block for the particle at xi moving at vi (the block's attribute 0: velocities).
// Built for AVX-512 (x86-64-v4), AVX2 and baseline x86-64, picked at load time: the same IEEE
// arithmetic on each (no contraction). AVX-512 took a 15M lighthouse frame's potentials from 150 to
// 118 ms (the square roots and the division per point).
SPUME_CLONES_FOR_AVX512_AND_AVX2 float velocity_difference(
    const BlockBuffer& block, const Vec3f& xi, const Vec3f& vi, float h2, float inv_h) {
  const size_t m = block.size();
  const float *bx = block.x(), *by = block.y(), *bz = block.z();
  const float *vx = block.attribute(0, 0), *vy = block.attribute(0, 1), *vz = block.attribute(0, 2);
  float diff[kLanes] = {};
  const float xix = xi.x(), xiy = xi.y(), xiz = xi.z(), vix = vi.x(), viy = vi.y(), viz = vi.z();
  for (size_t j = 0; j < m; j += kLanes)
    for (size_t l = 0; l < kLanes; ++l) {
      const float dx = bx[j + l] - xix, dy = by[j + l] - xiy, dz = bz[j + l] - xiz;
      const float d2 = std::min(dx * dx + dy * dy + dz * dz, 4.0f * h2);
      const float r = std::sqrt(d2);
      // Zero distance has no direction (MODEL.md §8.2) and beyond h has no weight (Eq. 3).
      const float has_direction = d2 > 0.0f ? 1.0f : 0.0f;
      const float w = has_direction * paper_weight_at(r * inv_h);
      const float inv_r = 1.0f / std::max(r, 1e-30f);
      const float ux = -dx * inv_r, uy = -dy * inv_r, uz = -dz * inv_r;  // x^_ij
      // Eq. 2: |v_ij| (1 - v^_ij . x^_ij) = |v_ij| - v_ij . x^_ij, zero-safe for v_ij = 0.
      const float wx = vix - vx[j + l], wy = viy - vy[j + l], wz = viz - vz[j + l];
      const float speed = std::sqrt(wx * wx + wy * wy + wz * wz);
      diff[l] += (speed - (wx * ux + wy * uy + wz * uz)) * w;
    }
  return lane_sum(diff);
}

}  // namespace

float crest_curvature(const NeighbourGrid& grid, std::span<const Vec3f> sorted_normal, uint32_t si, const Vec3f& ni,
                      float radius) {
  const auto points = grid.sorted_points();
  const Vec3f xi = points[si];
  const float inv_radius = 1.0f / radius;
  float sum = 0.0f;
  grid.for_each_neighbour_wide(xi, radius, [&](uint32_t j, float d2) {
    const Vec3f& nj = sorted_normal[j];
    // Itself and coincident particles have no direction (MODEL.md §8.2); interior ones no normal.
    if (d2 <= 0.0f || nj.squaredNorm() == 0.0f) return;
    const Vec3f x_ji = points[j] - xi;
    if (x_ji.dot(ni) >= 0.0f) return;  // Eq. 6: only neighbours behind the normal (a convex surface)
    const float distance = std::sqrt(d2);
    sum += (1.0f - ni.dot(nj)) * paper_weight_at(distance * inv_radius);  // Eq. 4 with W(x_ij, radius)
  });
  return sum;
}

void compute_normals(const NeighbourGrid& grid, float particle_volume, const DiffuseParams& params,
                     const SolidSet* solids, std::vector<Vec3f>& normals) {
  const bool see_solids = solids && !solids->empty();
  const float h = grid.support_radius(), inv_h2 = 1.0f / (h * h);
  const auto points = grid.sorted_points();
  const auto order = grid.sorted_to_original();
  const float full = 4.0f / 3.0f * std::numbers::pi_v<float> * h * h * h / particle_volume;
  const float max_neighbours = params.surface_neighbour_fraction * full;
  // grad c = V sum_j dW/dr (x_i - x_j)/r = V sigma/h^5 sum_j (f'(q)/q) (x_i - x_j), with the cubic
  // spline W = sigma/h^3 f(q), q = r/h, sigma = 8/pi (core/cubic_spline.h).
  const float scale = particle_volume * CubicSpline::kSigmaNumerator / (std::numbers::pi_v<float> * h * h * h * h * h);
  normals.assign(points.size(), Vec3f::Zero());
  for_each_cell_block(grid, {}, [&](uint32_t begin, uint32_t end, const BlockBuffer& block) {
    const size_t m = block.size();
    const float *bx = block.x(), *by = block.y(), *bz = block.z();
    for (uint32_t si = begin; si < end; ++si) {
      const float px = points[si].x(), py = points[si].y(), pz = points[si].z();
      // First the neighbour count (cheap): only sparse neighbourhoods can be surface (MODEL.md §8.10).
      float count[kLanes] = {};
      for (size_t j = 0; j < m; j += kLanes)
        for (size_t l = 0; l < kLanes; ++l) {
          const float dx = bx[j + l] - px, dy = by[j + l] - py, dz = bz[j + l] - pz;
          count[l] += (dx * dx + dy * dy + dz * dz) * inv_h2 <= 1.0f ? 1.0f : 0.0f;
        }
      // Next to a wall the count is scaled up to the water the wall stands for (MODEL.md §8.10-11).
      const float fluid_count = lane_sum(count);
      if (fluid_count >= max_neighbours) continue;  // solids only raise the count
      // The bounds settle most particles against walls (interior) without integrating.
      if (see_solids && wet_wall_count(fluid_count, solid_coverage_bounds(*solids, points[si], h).lo) >= max_neighbours)
        continue;
      const SolidCoverage cover = see_solids ? solid_coverage(*solids, points[si], h, true) : SolidCoverage{};
      const float free_share = std::max(1.0f - cover.fraction, 0.1f);
      if (wet_wall_count(fluid_count, cover.fraction) >= max_neighbours) continue;
      float gx[kLanes] = {}, gy[kLanes] = {}, gz[kLanes] = {};
      for (size_t j = 0; j < m; j += kLanes)
        for (size_t l = 0; l < kLanes; ++l) {
          const float dx = bx[j + l] - px, dy = by[j + l] - py, dz = bz[j + l] - pz;
          const float q2 = std::min((dx * dx + dy * dy + dz * dz) * inv_h2, 4.0f);
          const float q = std::sqrt(q2);
          const float dw = cubic_spline_slope(q, q2);
          // Itself or a coincident particle has no direction (MODEL.md §8.2): weight 0.
          const float f = q2 > 0.0f ? dw / q : 0.0f;
          gx[l] -= f * dx, gy[l] -= f * dy, gz[l] -= f * dz;  // (x_i - x_j) = -d
        }
      Vec3f gradient = scale * Vec3f(lane_sum(gx), lane_sum(gy), lane_sum(gz));
      // The wall adds the gradient of the water it replaces, as far as the free side is wet: under
      // water the two cancel (interior), at the waterline half of it keeps the normal pointing up.
      if (cover.fraction > 0.0f) {
        const float full_free = full * free_share;
        gradient += std::min(fluid_count / full_free, 1.0f) * cover.gradient;
      }
      const float magnitude = gradient.norm();
      if (magnitude * h >= params.surface_threshold && magnitude > 0.0f) normals[order[si]] = -gradient / magnitude;
    }
  });
}

void compute_potentials(const NeighbourGrid& grid, const FluidStepState& state, const DiffuseParams& params,
                        float particle_volume, const SolidSet* solids, FormationPotentials& out) {
  const size_t n = state.positions.size();
  if (params.k_wc > 0.0f) compute_normals(grid, particle_volume, params, solids, out.normals);
  else out.normals.assign(n, Vec3f::Zero());  // no crest emission: no normals needed
  out.trapped_air.assign(n, 0.0f);
  out.wave_crest.assign(n, 0.0f);
  out.kinetic.assign(n, 0.0f);

  const float h = grid.support_radius(), h2 = h * h, inv_h = 1.0f / h;
  const float crest_radius = std::clamp(params.crest_support, 1.0f, 2.0f) * h;
  const auto points = grid.sorted_points();
  const auto order = grid.sorted_to_original();
  // Kinetic energy first: Eq. 8 multiplies by I_k, so particles too slow to emit skip their sums.
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const float speed2 = state.velocities[i].squaredNorm();
      out.kinetic[i] = clamp_and_scale(0.5f * state.masses[i] * speed2, params.kinetic.lo, params.kinetic.hi);
    }
  });
  std::vector<Vec3f>& sorted_velocity = out.sorted_velocity;
  std::vector<Vec3f>& sorted_normal = out.sorted_normal;
  sorted_velocity.resize(n), sorted_normal.resize(n);
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t j = b; j < e; ++j) sorted_velocity[j] = state.velocities[order[j]], sorted_normal[j] = out.normals[order[j]];
  });

  parallel_for(grid.occupied_cell_count(), 16, [&](size_t cb, size_t ce) {
    BlockBuffer block;
    for (size_t c = cb; c < ce; ++c) {
      const uint32_t begin = grid.cell_begin(c), end = grid.cell_begin(c + 1);
      bool any = false;
      for (uint32_t si = begin; si < end; ++si) any |= out.kinetic[order[si]] > 0.0f;
      if (!any) continue;
      block.gather(grid, grid.occupied_key(c), {sorted_velocity});
      for (uint32_t si = begin; si < end; ++si) {
        const uint32_t i = order[si];
        if (out.kinetic[i] <= 0.0f) continue;
        const Vec3f xi = points[si], vi = state.velocities[i], ni = out.normals[i];
        const float surface = ni.squaredNorm() > 0.0f ? 1.0f : 0.0f;
        const float v_diff = velocity_difference(block, xi, vi, h2, inv_h);
        // Eq. 7 first: only surface particles moving along their normal form crests, and only they
        // need the wider curvature sum.
        const float speed = vi.norm();
        const bool moving_out = surface > 0.0f && speed > 0.0f && vi.dot(ni) >= 0.6f * speed;
        const float curvature = moving_out ? crest_curvature(grid, sorted_normal, si, ni, crest_radius) : 0.0f;
        out.trapped_air[i] = clamp_and_scale(v_diff, params.trapped_air.lo, params.trapped_air.hi);
        out.wave_crest[i] = clamp_and_scale(curvature, params.wave_crest.lo, params.wave_crest.hi);
      }
    }
  });
}

}  // namespace spume
