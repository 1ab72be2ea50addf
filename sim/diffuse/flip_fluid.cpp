#include "sim/diffuse/flip_fluid.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/core/parallel.h"
#include "sim/diffuse/poly6_sums.h"
#include "sim/grid/block_buffer.h"

namespace spume {

FlipMeasure FlipFluid::prepare(FluidStepState& state, float particle_radius, float h) {
  FlipMeasure m;
  const float spacing = 2.0f * particle_radius;
  m.nominal_count = 4.0f / 3.0f * std::numbers::pi_v<float> * h * h * h / (spacing * spacing * spacing);
  m.full_count = m.nominal_count;
  const size_t n = state.positions.size();
  if (n == 0) return m;

  const float reach = kVelocitySmoothing * h;
  grid_.build(state.positions, reach);
  const auto order = grid_.sorted_to_original();
  const auto points = grid_.sorted_points();
  sorted_velocity_.resize(n);
  for (size_t j = 0; j < n; ++j) sorted_velocity_[j] = state.velocities[order[j]];
  smoothed_.resize(n);
  counts_.resize(n);
  const float inv_reach2 = 1.0f / (reach * reach), h_q2 = (h * h) * inv_reach2;
  parallel_for(grid_.occupied_cell_count(), 16, [&](size_t cb, size_t ce) {
    BlockBuffer block;
    for (size_t c = cb; c < ce; ++c) {
      block.gather(grid_, grid_.occupied_key(c), {sorted_velocity_});
      for (uint32_t si = grid_.cell_begin(c); si < grid_.cell_begin(c + 1); ++si) {
        const uint32_t i = order[si];
        float weight_sum = 0.0f;  // at least the particle's own weight, 1
        poly6_sums(block, points[si], inv_reach2, h_q2, counts_[i], weight_sum, smoothed_[i]);
      }
    }
  });
  state.velocities.swap(smoothed_);

  // The frame's full neighbourhood: a high quantile of the counts (the interior's).
  std::vector<float>& sorted = counts_;
  const size_t q = std::min(n - 1, size_t(kFullCountQuantile * double(n)));
  std::nth_element(sorted.begin(), sorted.begin() + ptrdiff_t(q), sorted.end());
  m.full_count = sorted[q];
  // Fewer than an eighth of the nominal count: no interior to measure (spray, a thin sheet).
  if (m.full_count >= m.nominal_count / kMaxDensityRatio)
    m.density_ratio = std::min(m.full_count / m.nominal_count, kMaxDensityRatio);
  return m;
}

DiffuseParams at_density(const DiffuseParams& params, float ratio) {
  DiffuseParams p = params;
  p.spray_below *= ratio;
  p.bubble_above *= ratio;
  p.hysteresis *= ratio;
  p.trapped_air.lo *= ratio, p.trapped_air.hi *= ratio;
  // Eqs. 4-6 sum over surface neighbours only: an area density, ratio^(2/3).
  const float areal = std::cbrt(ratio * ratio);
  p.wave_crest.lo *= areal, p.wave_crest.hi *= areal;
  p.k_ta /= ratio;
  p.k_wc /= ratio;
  return p;
}

}  // namespace spume
