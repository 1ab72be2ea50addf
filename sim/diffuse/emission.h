#pragma once
// Turning potentials into new diffuse particles (MODEL.md §1 Eq. 8, §2, §5 lifetime, §8.3, §8.7).
#include <cstdint>
#include <vector>

#include "sim/core/rng.h"
#include "sim/diffuse/fluid_state.h"
#include "sim/diffuse/params.h"
#include "sim/diffuse/potentials.h"

namespace spume {

struct EmissionResult {
  uint64_t requested = 0;  // particles the potentials asked for this step, within the per-particle cap
  uint64_t emitted = 0;    // particles appended (fewer when the budget binds)
  uint64_t capped = 0;     // particles beyond the per-particle cap: asked for, never sampled
  bool budget_bound = false;
};

// Eq. 8 with stochastic rounding: floor(n_d) plus one with probability frac(n_d), so the expected
// count equals n_d for any dt. At most kMaxSamplesPerStep (4,095) per fluid particle and step: a
// diffuse id holds the sample index in 12 bits (core/frames.h), and a wider index would shorten the
// parent id or the birth step. What the cap cuts is counted, never silently lost.
struct RoundedEmission {
  uint32_t count = 0;   // particles to sample, at most kMaxSamplesPerStep
  uint64_t capped = 0;  // the rounded n_d beyond the cap (saturates at 2^64 - 1)
};
RoundedEmission round_emission_counted(float expected, const RandomKey& key);
uint32_t round_emission(float expected, const RandomKey& key);  // round_emission_counted(...).count

// Lifetime from the generation potentials (MODEL.md §5): lifetime_min at zero potential, lifetime_max
// at full potential, linear in P = I_k (k_ta I_ta + k_wc I_wc) / (k_ta + k_wc).
float emission_lifetime(const DiffuseParams& params, float i_ta, float i_wc, float i_k);

// Sample one particle in the cylinder of radius r_V around the fluid particle's path over dt (MODEL.md §2):
// the axis follows its motion x_f(t) -> x_f(t + dt) (`motion` = that displacement / dt), while the new
// particle's velocity is v_f(t) plus the radial offset, as printed.
void sample_cylinder(const Vec3f& x_f, const Vec3f& motion, const Vec3f& v_f, float dt, float radius,
                     const std::array<float, 4>& u,
                     Vec3f& x_d, Vec3f& v_d);

// Per-fluid-particle counts and offsets, kept between steps by a caller that emits every step.
struct EmissionBuffers {
  std::vector<uint32_t> counts;
  std::vector<uint64_t> offsets;
  std::vector<uint32_t> parents;  // per particle the last call appended: its fluid particle's index in the state
};

// Appends this step's new particles to `out` (ids, positions, velocities, lifetimes; types are set by
// the next classification). `step` is the global diffuse step; the budget counts out.size() as alive.
EmissionResult emit_diffuse(const FluidStepState& state, const FormationPotentials& potentials,
                            const DiffuseParams& params, uint32_t step, float dt, float particle_radius,
                            DiffuseFrame& out);
EmissionResult emit_diffuse(const FluidStepState& state, const FormationPotentials& potentials,
                            const DiffuseParams& params, uint32_t step, float dt, float particle_radius,
                            DiffuseFrame& out, EmissionBuffers& buffers);

}  // namespace spume
