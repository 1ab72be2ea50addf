#pragma once
// Small fluids for tests, built by hand: lattices of spacing 2r, states and frames around them, and
// two blocks of water thrown at each other (the inputs of the tests through the spume binary).
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
  for (auto& p : points) {
    // One draw a statement: the order of a call's arguments is the compiler's choice.
    const float dx = u(rng), dy = u(rng), dz = u(rng);
    p += Vec3f(dx, dy, dz);
  }
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

// Frame k of two cubes of side `side` on a 0.04 m lattice (radius 0.02 m) closing in along x, 0.04 m
// nearer each other at every frame: the first from x = 0.04 k, the second from x = apart - 0.04 k;
// the first moves at `velocity`, the second at its mirror image (x negated). Points alternate
// between the two cubes.
inline FluidFrame blocks_closing_in(int k, float side, float apart, const Vec3f& velocity) {
  const std::vector<Vec3f> block = lattice(Vec3f(0, 0, 0), Vec3f(side, side, side), 0.04f);
  std::vector<Vec3f> x, v;
  for (const Vec3f& p : block) {
    x.push_back(p + Vec3f(0.04f * k, 0, 0)), v.push_back(velocity);
    x.push_back(p + Vec3f(apart - 0.04f * k, 0, 0)), v.push_back(Vec3f(-velocity.x(), velocity.y(), velocity.z()));
  }
  return frame_of(k, 0, x, v);
}

}  // namespace spume::testing
