#pragma once
// Small fluids for tests, built by hand: lattices of spacing 2r, and states around them.
#include <random>
#include <vector>

#include "sim/core/frames.h"
#include "sim/diffuse/fluid_state.h"

namespace spume::testing {

// Lattice points of spacing `spacing` filling [lo, hi] (inclusive of lo, centres at lo + k*spacing).
inline std::vector<Vec3f> lattice(const Vec3f& lo, const Vec3f& hi, float spacing) {
  std::vector<Vec3f> p;
  for (float z = lo.z(); z <= hi.z() + 1e-6f; z += spacing)
    for (float y = lo.y(); y <= hi.y() + 1e-6f; y += spacing)
      for (float x = lo.x(); x <= hi.x() + 1e-6f; x += spacing) p.emplace_back(x, y, z);
  return p;
}

inline void jitter(std::vector<Vec3f>& points, float amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-amount, amount);
  for (auto& p : points) p += Vec3f(u(rng), u(rng), u(rng));
}

inline FluidStepState state_of(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& velocities,
                               float mass = 1.0f) {
  FluidStepState s;
  s.positions = positions;
  s.velocities = velocities;
  s.motion = velocities;
  s.masses.assign(positions.size(), mass);
  for (uint32_t i = 0; i < positions.size(); ++i) s.ids.push_back(i);
  return s;
}

inline FluidFrame frame_of(int index, double time, const std::vector<Vec3f>& positions,
                           const std::vector<Vec3f>& velocities) {
  FluidFrame f;
  f.index = index;
  f.time = time;
  f.positions = positions;
  f.velocities = velocities;
  for (uint32_t i = 0; i < positions.size(); ++i) f.ids.push_back(i);
  return f;
}

}  // namespace spume::testing
