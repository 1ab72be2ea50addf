#pragma once
// For cache tests: a diffuse frame of n particles spread uniformly over a 2 x 0.5 x 1 m box, with
// distinct ids, all three types and fixed-seed values (the same frame on every call).
#include <random>

#include "sim/core/frames.h"

namespace spume::testing {

inline DiffuseFrame spread_diffuse_frame(size_t n) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  DiffuseFrame d;
  d.index = 40, d.time = 1.6;
  d.resize(n);
  for (size_t i = 0; i < n; ++i) {
    d.ids[i] = diffuse_id(uint32_t(i), 3, 0);
    d.positions[i] = Vec3f(2 * u(rng), 0.5f * u(rng), u(rng));
    d.velocities[i] = Vec3f(u(rng), -u(rng), 0.1f);
    d.lifetimes[i] = 2 * u(rng);
    d.types[i] = DiffuseType(i % 3);
  }
  return d;
}

}  // namespace spume::testing
