// FLIP particles as what they are (MODEL.md §9.2): particle-scale velocity noise forms nothing, and
// the same water classifies alike however many particles the solver keeps in it.
#include <gtest/gtest.h>

#include <random>

#include "sim/diffuse/simulator.h"
#include "sim/scene/diffuse_params_reader.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

constexpr float kR = 0.02f, kS = 2 * kR, kH = 4 * kR;
constexpr float kSide = 15 * kS;  // a cube of 16 particles a side

DiffuseSetup setup_for(FluidParticles particles) {
  DiffuseSetup s;
  s.fluid.particle_radius = kR;
  s.fluid.support_radius = kH;
  s.params = read_diffuse_params(ParamReader::from_json(Json::object(), "test"), s.fluid, Vec3f(0, -9.81f, 0));
  s.particles = particles;
  return s;
}

TEST(FlipParticles, NoisyVelocitiesOfWaterAtRestFormNothing) {
  // A jittered cube standing still (same positions in both frames) whose stored velocities are noise,
  // uniform in [-1.5, 1.5] m/s per component (seeded). By hand: as SPH particles, most have |v| above
  // the energy band's 0.7 m/s, and Eq. 2 sums |v_ij| ~ 1.7 m/s over sum W ~ 8 (33 neighbours at a mean
  // weight of 1/4), far above tau_ta = 2 m/s: trapped air everywhere. Averaged over 2h (about 90
  // effective neighbours in the interior, 11 at a corner), a component's noise falls from 0.87 m/s to
  // 0.09-0.26 m/s, and Eq. 2 on the averaged field sums differences of that size: below both bands.
  auto x = testing::lattice(Vec3f::Zero(), Vec3f::Constant(kSide), kS);
  testing::jitter(x, 0.15f * kS, 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> noise(-1.5f, 1.5f);
  std::vector<Vec3f> v(x.size());
  for (Vec3f& vi : v) vi = Vec3f(noise(rng), noise(rng), noise(rng));
  const FluidFrame a = testing::frame_of(0, 0.0, x, v), b = testing::frame_of(1, 0.02, x, v);
  auto emitted = [&](FluidParticles particles) {
    DiffuseSimulator sim(setup_for(particles));
    sim.process_frame(a, &b, [](const DiffuseFrame&, const FrameStats&) {});
    return sim.particles().size();
  };
  EXPECT_GT(emitted(FluidParticles::Sph), 1000u);  // the paper's model on these particles
  EXPECT_EQ(emitted(FluidParticles::Flip), 0u);
}

// A probe just above the cube's top face, one in its interior, one 2h beside it.
std::vector<Vec3f> probes() {
  return {Vec3f(kSide / 2 + 0.25f * kS, kSide + 0.6f * kS, kSide / 2 + 0.25f * kS),  // on the top face: foam
          Vec3f::Constant(kSide / 2 + 0.25f * kS),                                    // inside: bubble
          Vec3f(kSide + 2 * kH, kSide / 2, kSide / 2)};                               // clear of it: spray
}

TEST(FlipParticles, DoublingTheParticleCountKeepsTheClassification) {
  // Frame 0: the cube on a lattice of spacing 2r. Frame 1: the same cube with a second lattice
  // offset by half a spacing on every axis (a reseeding solver doubling its particles). By hand: the
  // probe 0.6 spacings above the top layer reaches the layers 0.6 and 1.6 spacings below it within
  // h = 2 spacings, discs of radius 1.91 and 1.2 spacings: about 11.5 + 4.5 = 16 particles at frame 0,
  // foam; frame 1 adds the second lattice's top layer 1.1 spacings below (radius 1.67: about 8.8),
  // about 25: a bubble to the SPH limits (20), foam at the frame's own density (limits x 2: 12, 40).
  const auto coarse = testing::lattice(Vec3f::Zero(), Vec3f::Constant(kSide), kS);
  auto dense = coarse;
  for (const Vec3f& p : testing::lattice(Vec3f::Constant(kS / 2), Vec3f::Constant(kSide - kS / 2), kS))
    dense.push_back(p);
  std::vector<FluidFrame> frames;
  const std::vector<Vec3f>* const both[] = {&coarse, &dense};
  for (const std::vector<Vec3f>* x : both) {
    FluidFrame f;
    f.index = int(frames.size());
    f.time = 0.02 * f.index;
    f.positions = *x;
    f.velocities.assign(x->size(), Vec3f::Zero());  // no ids: a FLIP export
    frames.push_back(f);
  }
  auto types_at = [&](FluidParticles particles) {
    DiffuseSetup setup = setup_for(particles);
    setup.params.gravity = Vec3f::Zero();  // probes stay where they are
    setup.params.buoyancy = 0.0f;
    setup.params.k_ta = setup.params.k_wc = 0.0f;
    setup.fill_narrow_band = false;
    DiffuseSimulator sim(setup);
    const auto p = probes();
    DiffuseFrame d;
    d.resize(p.size());
    for (uint32_t i = 0; i < p.size(); ++i) {
      d.ids[i] = diffuse_id(i, kMaxBirthStep, 0);
      d.positions[i] = p[i], d.velocities[i] = Vec3f::Zero(), d.lifetimes[i] = 1.0f, d.types[i] = DiffuseType::Foam;
    }
    sim.set_particles(d);
    std::vector<std::vector<DiffuseType>> types;
    auto record = [&](const DiffuseFrame& f, const FrameStats&) {
      types.emplace_back(p.size());
      for (size_t k = 0; k < f.size(); ++k) types.back()[diffuse_id_parent(f.ids[k])] = f.types[k];
    };
    sim.process_frame(frames[0], &frames[1], record);
    sim.process_frame(frames[1], nullptr, record);
    return types;
  };
  const std::vector<DiffuseType> expected = {DiffuseType::Foam, DiffuseType::Bubble, DiffuseType::Spray};
  const auto flip = types_at(FluidParticles::Flip);
  EXPECT_EQ(flip[0], expected);
  EXPECT_EQ(flip[1], expected);
  const auto sph = types_at(FluidParticles::Sph);
  EXPECT_EQ(sph[0], expected);
  EXPECT_EQ(sph[1][0], DiffuseType::Bubble);  // the paper's fixed count: the surface went under
}

TEST(FlipParticles, DensityIsMeasuredFromTheFrame) {
  // The interior of the doubled lattice counts twice the nominal 33.5 (the 90% quantile of the
  // counts lies in the interior of a 16^3 cube, 42% of its particles).
  auto x = testing::lattice(Vec3f::Zero(), Vec3f::Constant(kSide), kS);
  for (const Vec3f& p : testing::lattice(Vec3f::Constant(kS / 2), Vec3f::Constant(kSide - kS / 2), kS)) x.push_back(p);
  testing::jitter(x, 0.05f * kS, 5);
  FluidStepState state = testing::state_of(x, std::vector<Vec3f>(x.size(), Vec3f(0.5f, 0, 0)));
  FlipFluid flip;
  const FlipMeasure m = flip.prepare(state, kR, kH);
  EXPECT_NEAR(m.nominal_count, 4.0f / 3.0f * 3.14159265f * 8.0f, 1e-3f);
  EXPECT_NEAR(m.density_ratio, 2.0f, 0.15f);
  for (const Vec3f& v : state.velocities) ASSERT_NEAR((v - Vec3f(0.5f, 0, 0)).norm(), 0.0f, 1e-5f);  // uniform stays
  const DiffuseParams p = at_density(setup_for(FluidParticles::Flip).params, 2.0f);
  EXPECT_FLOAT_EQ(p.bubble_above, 40.0f);
  EXPECT_FLOAT_EQ(p.spray_below, 12.0f);
}

}  // namespace
}  // namespace spume
