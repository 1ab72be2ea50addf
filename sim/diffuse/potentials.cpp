#include "potentials.h"

#include <numbers>

#include "core/parallel.h"
#include "diffuse/kernels.h"

namespace spume {

void compute_normals(const NeighbourGrid& grid, float particle_volume, const DiffuseParams& params,
                     std::vector<Vec3f>& normals) {
  const float h = grid.support_radius();
  const CubicSpline kernel(h);
  const auto points = grid.sorted_points();
  const auto order = grid.sorted_to_original();
  const float full = 4.0f / 3.0f * std::numbers::pi_v<float> * h * h * h / particle_volume;
  const float max_neighbours = params.surface_neighbour_fraction * full;
  normals.assign(points.size(), Vec3f::Zero());
  parallel_for(points.size(), 1024, [&](size_t b, size_t e) {
    for (size_t si = b; si < e; ++si) {
      const Vec3f xi = points[si];
      Vec3f gradient = Vec3f::Zero();
      int neighbours = 0;
      grid.for_each_neighbour(xi, h, [&](uint32_t sj, float d2) {
        ++neighbours;
        if (d2 <= 0.0f) return;  // itself, or a coincident particle: no direction (MODEL.md §8.2)
        const float r = std::sqrt(d2);
        gradient += (kernel.derivative(r) / r) * (xi - points[sj]);
      });
      gradient *= particle_volume;
      const float magnitude = gradient.norm();
      if (magnitude * h >= params.surface_threshold && magnitude > 0.0f && float(neighbours) < max_neighbours)
        normals[order[si]] = -gradient / magnitude;
    }
  });
}

void compute_potentials(const NeighbourGrid& grid, const FluidStepState& state, const DiffuseParams& params,
                        float particle_volume, FormationPotentials& out) {
  const size_t n = state.positions.size();
  if (params.k_wc > 0.0f) compute_normals(grid, particle_volume, params, out.normals);
  else out.normals.assign(n, Vec3f::Zero());  // no crest emission: no normals needed
  out.trapped_air.assign(n, 0.0f);
  out.wave_crest.assign(n, 0.0f);
  out.kinetic.assign(n, 0.0f);

  const float h = grid.support_radius();
  const auto points = grid.sorted_points();
  const auto order = grid.sorted_to_original();
  parallel_for(n, 1024, [&](size_t b, size_t e) {
    for (size_t si = b; si < e; ++si) {
      const uint32_t i = order[si];
      const Vec3f xi = points[si], vi = state.velocities[i], ni = out.normals[i];
      const float speed = vi.norm();
      const float energy = 0.5f * state.masses[i] * speed * speed;
      out.kinetic[i] = clamp_and_scale(energy, params.kinetic.lo, params.kinetic.hi);
      if (out.kinetic[i] <= 0.0f) continue;  // Eq. 8 multiplies by I_k: too slow to emit, skip the sums
      const bool surface = ni.squaredNorm() > 0.0f;
      float v_diff = 0.0f, curvature = 0.0f;
      grid.for_each_neighbour(xi, h, [&](uint32_t sj, float d2) {
        if (d2 <= 0.0f) return;  // MODEL.md §8.2: no direction, no contribution
        const uint32_t j = order[sj];
        const float r = std::sqrt(d2);
        const Vec3f x_ij = (xi - points[sj]) / r;  // unit
        const float w = paper_weight(r, h);
        // Eq. 2: |v_ij| (1 - v^_ij . x^_ij) = |v_ij| - v_ij . x^_ij, which is zero-safe for v_ij = 0.
        const Vec3f v_ij = vi - state.velocities[j];
        v_diff += (v_ij.norm() - v_ij.dot(x_ij)) * w;
        // Eqs. 4-6: only convex neighbours (x^_ji . n_i < 0, i.e. x^_ij . n_i > 0) with a normal.
        const Vec3f& nj = out.normals[j];
        if (surface && nj.squaredNorm() > 0.0f && x_ij.dot(ni) > 0.0f) curvature += (1.0f - ni.dot(nj)) * w;
      });
      // Eq. 7: only particles moving along their normal form crests.
      const bool moving_out = surface && speed > 0.0f && vi.dot(ni) >= 0.6f * speed;
      out.trapped_air[i] = clamp_and_scale(v_diff, params.trapped_air.lo, params.trapped_air.hi);
      out.wave_crest[i] = clamp_and_scale(moving_out ? curvature : 0.0f, params.wave_crest.lo, params.wave_crest.hi);
    }
  });
}

}  // namespace spume
