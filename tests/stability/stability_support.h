#pragma once
// Shared checks of the stability suite: every value finite, every particle inside the domain, and a simulator run
// over a whole fluid sequence.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "sim/core/error.h"
#include "sim/diffuse/simulator.h"
#include "sim/scene/diffuse_params_reader.h"
#include "tests/support/error_of.h"
#include "tests/support/test_fluids.h"

namespace spume::stability {

using testing::error_of;

// Every diffuse value finite, every type valid, every lifetime finite (DiffuseFrame::validate checks
// exactly this; a failure names the particle).
inline ::testing::AssertionResult all_finite(const DiffuseFrame& f) {
  try {
    f.validate("diffuse frame");
  } catch (const Error& e) {
    return ::testing::AssertionFailure() << e.what();
  }
  return ::testing::AssertionSuccess();
}

inline ::testing::AssertionResult all_inside(const DiffuseFrame& f, const Aabb& domain) {
  for (size_t i = 0; i < f.size(); ++i)
    if (!domain.contains(f.positions[i]))
      return ::testing::AssertionFailure() << "diffuse particle " << i << " at " << f.positions[i].transpose()
                                           << " is outside the domain";
  return ::testing::AssertionSuccess();
}

// Scene defaults at radius r (Froude-scaled, as a scene without a `diffuse` object gets them), with
// `diffuse` keys set as in a scene file.
inline DiffuseSetup setup_with(float r, const Json& diffuse = Json::object(), double fps = 50.0) {
  DiffuseSetup s;
  s.fluid.particle_radius = r;
  s.fluid.support_radius = 4.0f * r;
  s.fluid.fps = fps;
  s.params = read_diffuse_params(ParamReader::from_json(diffuse, "stability"), s.fluid, Vec3f(0, -9.81f, 0));
  return s;
}

struct RunCheck {
  size_t max_particles = 0;  // the most diffuse particles alive at any frame
  uint64_t generated = 0, removed = 0, landed = 0, dropped = 0;
  std::vector<DiffuseFrame> frames;  // every frame's output, when kept
};

// Runs the whole sequence, asserting after every frame that all values are finite and (for a
// non-empty domain) that every particle lies inside it. Returns what happened.
inline RunCheck run_checked(DiffuseSimulator& sim, const std::vector<FluidFrame>& fluid, bool keep = false) {
  RunCheck r;
  const Aabb domain = sim.setup().domain;
  for (size_t k = 0; k < fluid.size(); ++k) {
    const FrameStats s = sim.process_frame(fluid[k], k + 1 < fluid.size() ? &fluid[k + 1] : nullptr,
                                           [&](const DiffuseFrame& f, const FrameStats&) {
                                             EXPECT_TRUE(all_finite(f)) << "frame " << k;
                                             if (!domain.empty()) {
                                               EXPECT_TRUE(all_inside(f, domain)) << "frame " << k;
                                             }
                                             r.max_particles = std::max(r.max_particles, f.size());
                                             if (keep) r.frames.push_back(f);
                                           });
    r.generated += s.generated;
    r.removed += s.removed;
    r.landed += s.landed;
    r.dropped += s.dropped;
  }
  EXPECT_TRUE(all_finite(sim.particles()));
  return r;
}

// A block of fluid on a lattice of spacing 2r translating at velocity v; frame k at time k * dt.
inline std::vector<FluidFrame> translating_block(const Vec3f& lo, const Vec3f& hi, float r, const Vec3f& v, double dt,
                                                 int frames) {
  const auto x0 = testing::lattice(lo, hi, 2 * r);
  std::vector<FluidFrame> out;
  for (int k = 0; k < frames; ++k) {
    std::vector<Vec3f> x(x0.size());
    for (size_t i = 0; i < x.size(); ++i) x[i] = x0[i] + float(k * dt) * v;
    out.push_back(testing::frame_of(k, k * dt, x, std::vector<Vec3f>(x.size(), v)));
  }
  return out;
}

// Two lattice blocks of side `side` thrown at each other along x at `speed` (m/s each), with an upward
// component, so trapped air, crests and kinetic energy all form; frame k at time k * dt. Their facing
// layers start 2r apart (in contact), so the first step already traps air whatever the speed.
inline std::vector<FluidFrame> colliding_blocks(float r, float side, float speed, double dt, int frames) {
  const float gap = r;
  auto a = testing::lattice(Vec3f(-side - gap, 0, 0), Vec3f(-gap, side, side), 2 * r);
  auto b = testing::lattice(Vec3f(gap, 0, 0), Vec3f(side + gap, side, side), 2 * r);
  std::vector<Vec3f> x0 = a, v;
  x0.insert(x0.end(), b.begin(), b.end());
  for (size_t i = 0; i < x0.size(); ++i) v.push_back(i < a.size() ? Vec3f(speed, 0.5f * speed, 0) : Vec3f(-speed, 0.5f * speed, 0));
  std::vector<FluidFrame> out;
  for (int k = 0; k < frames; ++k) {
    std::vector<Vec3f> x(x0.size());
    for (size_t i = 0; i < x.size(); ++i) x[i] = x0[i] + float(k * dt) * v[i];
    out.push_back(testing::frame_of(k, k * dt, x, v));
  }
  return out;
}

// Diffuse particles of one type at the given positions, at rest, born long ago (so not newborn).
inline DiffuseFrame diffuse_at(const std::vector<Vec3f>& positions, DiffuseType type,
                               const Vec3f& velocity = Vec3f::Zero()) {
  DiffuseFrame d;
  d.resize(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    d.positions[i] = positions[i];
    d.velocities[i] = velocity;
    d.lifetimes[i] = 100.0f;
    d.types[i] = type;
    d.ids[i] = diffuse_id(uint32_t(i), 500, 0);
  }
  return d;
}

}  // namespace spume::stability
