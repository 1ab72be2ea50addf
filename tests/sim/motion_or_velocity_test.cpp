// Which fluid velocity each equation uses (MODEL.md §1, §2), on fluids whose motion between frames,
// (x(t + dt) - x(t)) / dt, differs from their stored velocity v_f(t): an impact (two blocks meeting
// at 3 m/s that stand still by the next frame) and a droplet thrown upwards that falls back under
// gravity between two frames. The sampling cylinder's axis follows the motion; its particles' velocity,
// I_k, Eq. 2 (trapped air) and Eq. 7 (moving along the normal) use v_f(t). Each test fails when the
// two are swapped in that one place.
#include <gtest/gtest.h>

#include <cmath>

#include "sim/diffuse/emission.h"
#include "sim/diffuse/potentials.h"
#include "sim/diffuse/simulator.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

constexpr float kR = 0.02f, kH = 4 * kR;
constexpr float kRestDensity = 1000.0f;
const float kMass = kRestDensity * 8 * kR * kR * kR;  // 0.064 kg

// Two 4 x 4 x 4 blocks of spacing 2r, 2r apart across x = 0.14: the left one moving +x at 3 m/s,
// the right one -x, at t = 0; at t = 0.02 s they stand where they stood, stopped by the impact.
struct Impact {
  FluidFrame a, b;
  std::vector<bool> interface;  // in the two layers facing each other (x = 0.12 and x = 0.16)
};

Impact impact() {
  auto left = testing::lattice(Vec3f(0, 0, 0), Vec3f(0.12f, 0.12f, 0.12f), 2 * kR);
  const auto right = testing::lattice(Vec3f(0.16f, 0, 0), Vec3f(0.28f, 0.12f, 0.12f), 2 * kR);
  std::vector<Vec3f> v(left.size(), Vec3f(3, 0, 0));
  v.resize(left.size() + right.size(), Vec3f(-3, 0, 0));
  left.insert(left.end(), right.begin(), right.end());
  Impact f{testing::frame_of(0, 0.0, left, v), testing::frame_of(1, 0.02, left, std::vector<Vec3f>(left.size(), Vec3f::Zero())), {}};
  for (const Vec3f& p : left) f.interface.push_back(std::abs(p.x() - 0.14f) < 0.03f);
  return f;
}

DiffuseParams impact_params() {
  DiffuseParams p;
  p.kinetic = {0.01f, 0.1f};     // E_k = m 9 / 2 = 0.288 J at 3 m/s: I_k = 1; at rest 0
  p.trapped_air = {0.5f, 5.0f};  // the layers facing each other: >= |v_ij| 2 W = 6 2 0.5 = 6 from one neighbour
  p.k_ta = 2000.0f, p.k_wc = 0.0f;
  return p;
}

FluidStepState state_between(const FluidFrame& a, const FluidFrame& b) {
  FluidStepState s;
  interpolate_fluid(pair_frames(a, &b, b.time - a.time), 0.0f, kMass, s);
  return s;
}

FormationPotentials potentials_of(const FluidStepState& s, const DiffuseParams& params, float h) {
  NeighbourGrid grid;
  grid.build(s.positions, h);
  FormationPotentials out;
  compute_potentials(grid, s, params, 8 * kR * kR * kR, nullptr, out);
  return out;
}

TEST(MotionOrVelocity, TheImpactsStateHoldsBothAsMeasured) {
  const Impact f = impact();
  const FluidStepState s = state_between(f.a, f.b);
  for (size_t i = 0; i < s.positions.size(); ++i) {
    ASSERT_EQ(s.motion[i], Vec3f::Zero());
    ASSERT_EQ(s.velocities[i], f.a.velocities[i]);
  }
}

TEST(MotionOrVelocity, KineticEnergyAndTrappedAirUseTheStoredVelocity) {
  // At t the blocks meet at 3 m/s: I_k = 1 everywhere (from v_f(t); the motion is zero), and the two
  // facing layers trap air: each of their particles has a neighbour across at h / 2 (W = 1/2)
  // closing at 6 m/s, v_diff >= 6 (1 - (-1)) / 2 = 6 >= tau_ta max, so I_ta = 1. The motion would
  // give I_k = 0 and v_ij = 0.
  const Impact f = impact();
  const FormationPotentials p = potentials_of(state_between(f.a, f.b), impact_params(), kH);
  int facing = 0;
  for (size_t i = 0; i < f.a.size(); ++i) {
    EXPECT_EQ(p.kinetic[i], 1.0f) << i;
    if (!f.interface[i]) continue;
    ++facing;
    EXPECT_EQ(p.trapped_air[i], 1.0f) << f.a.positions[i].transpose();
  }
  EXPECT_EQ(facing, 32);
}

// Checks every new particle against its parent: within r_V of the parent's path along `motion` over
// dt, and with velocity v_f(t) plus the radial offset from that axis (MODEL.md §2).
void expect_sampled_along_motion(const DiffuseFrame& out, size_t first, const FluidStepState& s, float dt) {
  for (size_t k = first; k < out.size(); ++k) {
    const uint32_t parent = diffuse_id_parent(out.ids[k]);
    ASSERT_LT(parent, s.positions.size());
    const Vec3f d = out.positions[k] - s.positions[parent];
    const Vec3f m = s.motion[parent];
    const float length = m.norm() * dt;
    const Vec3f axis = m.norm() > 0 ? Vec3f(m.normalized()) : Vec3f::Zero();
    const float along = d.dot(axis);
    const Vec3f radial = d - along * axis;
    ASSERT_GE(along, -1e-5f) << k;
    ASSERT_LE(along, length + 1e-5f) << k;
    ASSERT_LE(radial.norm(), kR + 1e-5f) << k;
    ASSERT_LT((out.velocities[k] - s.velocities[parent] - radial).norm(), 1e-4f) << k;
  }
}

TEST(MotionOrVelocity, NewParticlesLieAlongTheMotionWithTheStoredVelocity) {
  // The impact: the blocks do not move over the step, so the cylinder has no length and every new
  // particle lies on the disc of radius r around its parent; its velocity is +-3 m/s plus the radial
  // offset. Swapped, they would spread 0.06 m along x and move only with the offset.
  const Impact f = impact();
  const FluidStepState s = state_between(f.a, f.b);
  const DiffuseParams params = impact_params();
  const FormationPotentials p = potentials_of(s, params, kH);
  DiffuseFrame out;
  const EmissionResult r = emit_diffuse(s, p, params, 3, 0.02f, kR, out);
  ASSERT_GE(r.emitted, 1280u);  // 32 facing particles with I_k = I_ta = 1 x 2000/s x 0.02 s
  expect_sampled_along_motion(out, 0, s, 0.02f);
}

// A droplet (lattice points within 0.1 m of its centre, spacing 0.02 m) thrown up at 3 m/s, frames
// 1 s apart: by the next frame it has fallen 3 - g / 2 = -1.905 m. Its stored velocity at t points
// up, its motion over the frame down.
constexpr float kDropR = 0.01f, kDropH = 4 * kDropR;
struct Droplet {
  FluidFrame a, b;
};
Droplet droplet() {
  std::vector<Vec3f> ball;
  for (const Vec3f& p : testing::lattice(Vec3f::Constant(-0.1f), Vec3f::Constant(0.1f), 2 * kDropR))
    if (p.norm() <= 0.1f + 1e-4f) ball.push_back(p);
  std::vector<Vec3f> later = ball;
  const float fall = 3.0f - 0.5f * 9.81f;
  for (Vec3f& p : later) p.y() += fall;
  return {testing::frame_of(0, 0.0, ball, std::vector<Vec3f>(ball.size(), Vec3f(0, 3, 0))),
          testing::frame_of(1, 1.0, later, std::vector<Vec3f>(ball.size(), Vec3f(0, 3.0f - 9.81f, 0)))};
}

DiffuseParams droplet_params() {
  DiffuseParams p;
  p.kinetic = {1e-4f, 1e-3f};    // m = 8e-3 kg: I_k = 1 at 3 m/s and at 1.9 m/s alike
  p.wave_crest = {0.01f, 0.5f};  // low: any convex curvature counts, whatever the crest's scale
  p.k_ta = 0.0f, p.k_wc = 100.0f;
  return p;
}

TEST(MotionOrVelocity, EquationSevenUsesTheStoredVelocity) {
  // Eq. 7 keeps particles whose v_f(t) is within acos 0.6 of their normal: on the rising droplet the
  // upper cap (n_y >= 0.6), never its lower half. With the motion (down) it would be the lower cap.
  const Droplet d = droplet();
  FluidStepState s;
  interpolate_fluid(pair_frames(d.a, &d.b, 1.0), 0.0f, kRestDensity * 8 * kDropR * kDropR * kDropR, s);
  ASSERT_LT(s.motion[0].y(), -1.9f);
  ASSERT_EQ(s.velocities[0], Vec3f(0, 3, 0));
  NeighbourGrid grid;
  grid.build(s.positions, kDropH);
  FormationPotentials p;
  compute_potentials(grid, s, droplet_params(), 8 * kDropR * kDropR * kDropR, nullptr, p);
  int crests = 0;
  for (size_t i = 0; i < s.positions.size(); ++i) {
    if (p.wave_crest[i] <= 0.0f) continue;
    ++crests;
    EXPECT_GE(p.normals[i].y(), 0.6f) << s.positions[i].transpose();
    EXPECT_GT(s.positions[i].y(), 0.0f) << s.positions[i].transpose();
  }
  EXPECT_GT(crests, 10);

  // The new particles of the crest particles: along the fall (the motion), moving up at 3 m/s.
  DiffuseFrame out;
  const EmissionResult r = emit_diffuse(s, p, droplet_params(), 0, 1.0f, kDropR, out);
  ASSERT_GT(r.emitted, 100u);
  for (size_t k = 0; k < out.size(); ++k) {
    const uint32_t parent = diffuse_id_parent(out.ids[k]);
    EXPECT_LT(out.positions[k].y(), s.positions[parent].y() + kDropR + 1e-5f) << k;
    EXPECT_GT(out.velocities[k].y(), 3.0f - kDropR - 1e-4f) << k;
  }
  expect_sampled_along_motion(out, 0, s, 1.0f);
}

TEST(MotionOrVelocity, TheSimulatorEmitsFromTheStoredVelocityAlongTheMotion) {
  // The impact through DiffuseSimulator: the particles born over the step, output at the second
  // frame, lie on their parents' discs and carry v_f(t) = +-3 m/s plus their offset; there are at
  // least as many as Eq. 8 asks of the facing layers (I_k = I_ta = 1: 2000/s x 0.02 s = 40 each, 1280
  // in all).
  const Impact f = impact();
  DiffuseSetup setup;
  setup.fluid.particle_radius = kR;
  setup.fluid.support_radius = kH;
  setup.fluid.rest_density = kRestDensity;
  setup.fluid.fps = 50.0;
  setup.params = impact_params();
  DiffuseSimulator sim(setup);
  DiffuseFrame born;
  sim.process_frame(f.a, &f.b, [](const DiffuseFrame&, const FrameStats&) {});
  const FrameStats stats = sim.process_frame(f.b, nullptr, [&](const DiffuseFrame& d, const FrameStats&) { born = d; });
  ASSERT_GT(born.size(), 0u);
  EXPECT_GE(born.size(), 1280u);
  EXPECT_EQ(stats.by_type[0] + stats.by_type[1] + stats.by_type[2], born.size());
  expect_sampled_along_motion(born, 0, state_between(f.a, f.b), 0.02f);
}

}  // namespace
}  // namespace spume
