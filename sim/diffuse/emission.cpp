#include "sim/diffuse/emission.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/core/rng.h"
#include "sim/diffuse/kernels.h"

namespace spume {
namespace {

uint64_t saturating_add(uint64_t a, uint64_t b) { return a > UINT64_MAX - b ? UINT64_MAX : a + b; }

}  // namespace

RoundedEmission round_emission_counted(float expected, const RandomKey& key) {
  if (!(expected > 0.0f)) return {};
  const double whole = std::floor(double(expected));
  const float u = random_uniform4(key)[0];
  const double rounded = whole + (double(u) < double(expected) - whole ? 1.0 : 0.0);  // +inf stays +inf
  constexpr double kCap = double(kMaxSamplesPerStep);
  if (rounded <= kCap) return {uint32_t(rounded), 0};
  const double beyond = rounded - kCap;
  constexpr double kMax = 18446744073709549568.0;  // the largest double below 2^64
  return {kMaxSamplesPerStep, beyond < kMax ? uint64_t(beyond) : uint64_t(kMax)};
}

uint32_t round_emission(float expected, const RandomKey& key) { return round_emission_counted(expected, key).count; }

float emission_lifetime(const DiffuseParams& params, float i_ta, float i_wc, float i_k) {
  const float rates = params.k_ta + params.k_wc;
  const float potential = rates > 0.0f ? i_k * (params.k_ta * i_ta + params.k_wc * i_wc) / rates : 0.0f;
  return params.lifetime_min + (params.lifetime_max - params.lifetime_min) * std::clamp(potential, 0.0f, 1.0f);
}

void sample_cylinder(const Vec3f& x_f, const Vec3f& motion, const Vec3f& v_f, float dt, float radius,
                     const std::array<float, 4>& u, Vec3f& x_d, Vec3f& v_d) {
  const float speed = motion.norm();
  // A particle that does not move has no axis; its cylinder has zero length and any frame will do
  // (MODEL.md §8.2).
  const Vec3f axis = speed > 0.0f ? Vec3f(motion / speed) : Vec3f::UnitY();
  Vec3f e1, e2;
  orthonormal_basis(axis, e1, e2);
  const float r = radius * std::sqrt(u[0]);  // sqrt: uniform over the disc (MODEL.md §8.7)
  const float theta = 2.0f * std::numbers::pi_v<float> * u[1];
  const float along = u[2] * dt * speed;
  const Vec3f radial = r * std::cos(theta) * e1 + r * std::sin(theta) * e2;
  x_d = x_f + radial + along * axis;
  v_d = radial + v_f;  // as printed: the radial offset doubles as a (small) velocity
}

EmissionResult emit_diffuse(const FluidStepState& state, const FormationPotentials& potentials,
                            const DiffuseParams& params, uint32_t step, float dt, float particle_radius,
                            DiffuseFrame& out) {
  EmissionBuffers buffers;
  return emit_diffuse(state, potentials, params, step, dt, particle_radius, out, buffers);
}

EmissionResult emit_diffuse(const FluidStepState& state, const FormationPotentials& potentials,
                            const DiffuseParams& params, uint32_t step, float dt, float particle_radius,
                            DiffuseFrame& out, EmissionBuffers& buffers) {
  const size_t n = state.positions.size();
  std::vector<uint32_t>& counts = buffers.counts;
  counts.resize(n);
  std::atomic<uint64_t> capped{0};
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    uint64_t capped_here = 0;
    for (size_t i = b; i < e; ++i) {
      const float expected =
          potentials.kinetic[i] * (params.k_ta * potentials.trapped_air[i] + params.k_wc * potentials.wave_crest[i]) * dt;
      const RoundedEmission r =
          round_emission_counted(expected, {params.seed, RandomPurpose::EmissionRounding, step, state.ids[i], 0});
      counts[i] = r.count;
      capped_here = saturating_add(capped_here, r.capped);
    }
    // Integer sums: the total does not depend on how the loop was split. Saturating, like the parts.
    uint64_t seen = capped.load();
    while (!capped.compare_exchange_weak(seen, saturating_add(seen, capped_here))) {
    }
  });
  std::vector<uint64_t>& offsets = buffers.offsets;
  offsets.resize(n + 1);
  exclusive_scan(counts.data(), n, offsets.data());
  EmissionResult result;
  result.capped = capped.load();
  result.requested = offsets[n];
  if (result.requested >= (uint64_t(1) << 32))
    fail("emission: ", result.requested, " particles requested in one step; at most 2^32 - 1 are supported. "
         "Lower diffuse.k_ta / diffuse.k_wc or set diffuse.max_particles");

  // The emission budget: keep a uniformly random subset of the candidates (ranked by a hash of their
  // id), so that where the budget binds it thins emission evenly in space.
  std::vector<uint8_t> keep;
  uint64_t accepted = result.requested;
  if (params.max_particles) {
    const uint64_t room = *params.max_particles > out.size() ? *params.max_particles - out.size() : 0;
    if (result.requested > room) {
      result.budget_bound = true;
      accepted = room;
      std::vector<uint64_t> ranked(result.requested);  // (rank bits << 32 | candidate) is unique
      parallel_for(n, 4096, [&](size_t b, size_t e) {
        for (size_t i = b; i < e; ++i)
          for (uint32_t s = 0; s < counts[i]; ++s) {
            const uint64_t c = offsets[i] + s;
            const uint32_t rank = random_bits({params.seed, RandomPurpose::BudgetRank, step, state.ids[i], s})[0];
            ranked[c] = (uint64_t(rank) << 32) | (c & 0xffffffffu);
          }
      });
      keep.assign(result.requested, 0);
      if (room > 0) {
        std::nth_element(ranked.begin(), ranked.begin() + (room - 1), ranked.end());
        for (size_t k = 0; k < room; ++k) keep[ranked[k] & 0xffffffffu] = 1;
      }
    }
  }

  const size_t base = out.size();
  std::vector<uint64_t> slot;  // candidate -> output index, when some are dropped
  if (!keep.empty()) {
    slot.resize(result.requested);
    uint64_t next = 0;
    for (uint64_t c = 0; c < result.requested; ++c) slot[c] = keep[c] ? next++ : UINT64_MAX;
  }
  out.resize(base + accepted);
  buffers.parents.resize(accepted);
  result.emitted = accepted;
  parallel_for(n, 1024, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      if (counts[i] == 0) continue;
      const float lifetime = emission_lifetime(params, potentials.trapped_air[i], potentials.wave_crest[i],
                                               potentials.kinetic[i]);
      for (uint32_t s = 0; s < counts[i]; ++s) {
        const uint64_t c = offsets[i] + s;
        const uint64_t at = slot.empty() ? c : slot[c];
        if (at == UINT64_MAX) continue;
        const size_t k = base + at;
        const auto u = random_uniform4({params.seed, RandomPurpose::CylinderSample, step, state.ids[i], s});
        sample_cylinder(state.positions[i], state.motion[i], state.velocities[i], dt, particle_radius, u,
                        out.positions[k], out.velocities[k]);
        out.ids[k] = diffuse_id(state.ids[i], step, s);
        buffers.parents[at] = uint32_t(i);
        out.lifetimes[k] = lifetime;
        out.types[k] = DiffuseType::Spray;  // provisional: classified before any use
      }
    }
  });
  return result;
}

}  // namespace spume
