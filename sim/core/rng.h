#pragma once
// Counter-based random numbers (Philox4x32-10, Salmon et al., SC 2011). A draw is a pure function of
// its key and counter, so the numbers a particle gets never depend on thread scheduling or call
// order (MODEL.md §8.8). Key: the run's seed. Counter: what is being sampled.
#include <array>
#include <cstdint>

namespace spume {

// What a random number is for; part of the counter so that purposes never share a stream.
enum class RandomPurpose : uint32_t {
  EmissionRounding = 1,  // stochastic rounding of n_d (MODEL.md §8.3)
  CylinderSample = 2,    // X_r, X_theta, X_h of MODEL.md §2
  BudgetRank = 3,        // who emits when the emission budget binds
  Test = 99,
};

inline std::array<uint32_t, 4> philox4x32(std::array<uint32_t, 4> ctr, std::array<uint32_t, 2> key) {
  constexpr uint32_t M0 = 0xD2511F53u, M1 = 0xCD9E8D57u, W0 = 0x9E3779B9u, W1 = 0xBB67AE85u;
  for (int round = 0; round < 10; ++round) {
    const uint64_t p0 = uint64_t(M0) * ctr[0];
    const uint64_t p1 = uint64_t(M1) * ctr[2];
    ctr = {uint32_t(p1 >> 32) ^ ctr[1] ^ key[0], uint32_t(p1), uint32_t(p0 >> 32) ^ ctr[3] ^ key[1], uint32_t(p0)};
    key[0] += W0;
    key[1] += W1;
  }
  return ctr;
}

// Four uniform floats in [0,1) keyed by (seed, purpose, step, item, sample).
struct RandomKey {
  uint64_t seed = 0;
  RandomPurpose purpose = RandomPurpose::Test;
  uint32_t step = 0;    // global diffuse step (frame * substeps + substep)
  uint64_t item = 0;    // e.g. fluid particle id
  uint32_t sample = 0;  // sample index within the item
};

inline std::array<uint32_t, 4> random_bits(const RandomKey& k) {
  // The purpose folds into the key so that equal counters under different purposes are independent.
  const std::array<uint32_t, 2> key = {uint32_t(k.seed) ^ (uint32_t(k.purpose) * 0x85EBCA6Bu),
                                       uint32_t(k.seed >> 32) ^ uint32_t(k.purpose)};
  return philox4x32({k.step, uint32_t(k.item), uint32_t(k.item >> 32), k.sample}, key);
}

// 24 high bits -> float in [0,1): exactly representable, never 1.
inline float to_unit_float(uint32_t bits) { return float(bits >> 8) * (1.0f / 16777216.0f); }

inline std::array<float, 4> random_uniform4(const RandomKey& k) {
  const auto b = random_bits(k);
  return {to_unit_float(b[0]), to_unit_float(b[1]), to_unit_float(b[2]), to_unit_float(b[3])};
}

}  // namespace spume
