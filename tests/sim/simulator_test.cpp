// The diffuse simulator end to end on analytic fluids: determinism, solids, scale, walls.
#include <gtest/gtest.h>

#include <cstring>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/diffuse/simulator.h"
#include "sim/scene/diffuse_params_reader.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

// Two lattice blocks (r = 0.02 m * scale) thrown at each other; Froude-scaled by `scale`: lengths x s,
// velocities and times x sqrt(s). Frame k is at time k / fps.
std::vector<FluidFrame> colliding_blocks(int frames, float scale = 1.0f) {
  const float r = 0.02f * scale, spacing = 2 * r, vs = std::sqrt(scale);
  auto a = testing::lattice(Vec3f(0, 0, 0), Vec3f(0.4f, 0.4f, 0.4f) * scale, spacing);
  auto b = testing::lattice(Vec3f(0.5f, 0, 0) * scale, Vec3f(0.9f, 0.4f, 0.4f) * scale, spacing);
  std::vector<Vec3f> x0 = a, v;
  x0.insert(x0.end(), b.begin(), b.end());
  for (size_t i = 0; i < x0.size(); ++i) v.push_back(vs * (i < a.size() ? Vec3f(2, 1, 0) : Vec3f(-2, 1, 0)));
  std::vector<FluidFrame> out;
  const double fps = 50.0 / vs;
  for (int k = 0; k < frames; ++k) {
    std::vector<Vec3f> x(x0.size());
    for (size_t i = 0; i < x.size(); ++i) x[i] = x0[i] + float(k / fps) * v[i];
    out.push_back(testing::frame_of(k, k / fps, x, v));
  }
  return out;
}

DiffuseSetup setup_for(float scale, int substeps = 1) {
  DiffuseSetup s;
  s.fluid.particle_radius = 0.02f * scale;
  s.fluid.support_radius = 0.08f * scale;
  s.fluid.fps = 50.0 / std::sqrt(scale);
  // Scene defaults, Froude-scaled to this radius, with nothing set by hand.
  s.params = read_diffuse_params(ParamReader::from_json(Json::object(), "test"), s.fluid, Vec3f(0, -9.81f, 0));
  s.params.substeps = substeps;
  return s;
}

struct RunResult {
  std::vector<DiffuseFrame> frames;
  uint64_t generated = 0;
};

RunResult run(DiffuseSetup setup, const std::vector<FluidFrame>& fluid) {
  DiffuseSimulator sim(std::move(setup));
  RunResult result;
  for (size_t k = 0; k < fluid.size(); ++k) {
    const auto stats = sim.process_frame(fluid[k], k + 1 < fluid.size() ? &fluid[k + 1] : nullptr,
                                         [&](const DiffuseFrame& f, const FrameStats&) { result.frames.push_back(f); });
    result.generated += stats.generated;
  }
  return result;
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

TEST(DiffuseSimulator, OutputIsByteIdenticalForOneAndTwoThreads) {
  const auto fluid = colliding_blocks(8);
  set_thread_count(1);
  const RunResult one = run(setup_for(1.0f, 2), fluid);
  set_thread_count(2);
  const RunResult two = run(setup_for(1.0f, 2), fluid);
  set_thread_count(0);
  ASSERT_EQ(one.frames.size(), two.frames.size());
  ASSERT_GT(one.frames.back().size(), 1000u);  // the collision makes plenty
  for (size_t k = 0; k < one.frames.size(); ++k) {
    const auto &a = one.frames[k], &b = two.frames[k];
    ASSERT_TRUE(same_bytes(a.ids, b.ids)) << k;
    ASSERT_TRUE(same_bytes(a.positions, b.positions)) << k;
    ASSERT_TRUE(same_bytes(a.velocities, b.velocities)) << k;
    ASSERT_TRUE(same_bytes(a.lifetimes, b.lifetimes)) << k;
    ASSERT_TRUE(same_bytes(a.types, b.types)) << k;
  }
}

// A last frame (no next) frees the step's working arrays before its particles are handed out, so the
// caches' encoders can take that memory; a later frame grows them again, and the particles are those
// of a run that never stopped.
TEST(DiffuseSimulator, ALastFrameFreesTheStepsArraysAndALaterFrameCarriesOn) {
  const auto fluid = colliding_blocks(8);
  const RunResult whole = run(setup_for(1.0f, 2), fluid);
  ASSERT_GT(whole.frames.back().size(), 1000u);

  DiffuseSimulator sim(setup_for(1.0f, 2));
  auto ignore = [](const DiffuseFrame&, const FrameStats&) {};
  for (int k = 0; k < 4; ++k) sim.process_frame(fluid[k], &fluid[k + 1], ignore);
  const size_t particles = sim.particles().size();
  // Between steps: neighbour counts, fluid velocities, kernel sums (20 bytes a particle) at least.
  EXPECT_GE(sim.step_scratch_bytes(), 20 * particles);
  size_t held_when_handed_out = SIZE_MAX;
  sim.process_frame(fluid[4], nullptr, [&](const DiffuseFrame&, const FrameStats&) {
    held_when_handed_out = sim.step_scratch_bytes();
  });
  EXPECT_EQ(held_when_handed_out, 0u);
  for (int k = 4; k < 8; ++k) {
    DiffuseFrame got;
    const FluidFrame* next = k + 1 < 8 ? &fluid[k + 1] : nullptr;
    sim.process_frame(fluid[k], next, [&](const DiffuseFrame& f, const FrameStats&) { got = f; });
    const DiffuseFrame& want = whole.frames[k];
    ASSERT_TRUE(same_bytes(got.ids, want.ids)) << k;
    ASSERT_TRUE(same_bytes(got.positions, want.positions)) << k;
    ASSERT_TRUE(same_bytes(got.velocities, want.velocities)) << k;
    ASSERT_TRUE(same_bytes(got.lifetimes, want.lifetimes)) << k;
    ASSERT_TRUE(same_bytes(got.types, want.types)) << k;
  }
}

// The blocks of colliding_blocks(), plus two single-file jets meeting head-on around x = 2 (spacing
// 0.07 m > h/2 = 0.04 m, so fewer than six fluid particles are ever within h of a point there): air
// trapped where they meet is released as spray.
std::vector<FluidFrame> blocks_and_jets(int frames) {
  auto fluid = colliding_blocks(frames);
  for (auto& f : fluid) {
    uint32_t id = uint32_t(f.ids.size());
    for (int side : {-1, 1})
      for (int i = 0; i < 8; ++i, ++id) {
        const Vec3f v(-2.0f * side, 0, 0);
        f.positions.push_back(Vec3f(2.0f + side * (0.04f + 0.07f * i), 0.2f, 0.2f) + float(f.time) * v);
        f.velocities.push_back(v);
        f.ids.push_back(id);
      }
  }
  return fluid;
}

TEST(DiffuseSimulator, SprayFoamAndBubblesFormWhereExpected) {
  const RunResult r = run(setup_for(1.0f), blocks_and_jets(10));
  const DiffuseFrame& last = r.frames.back();
  size_t counts[3] = {0, 0, 0};
  for (size_t i = 0; i < last.size(); ++i) {
    const Vec3f& p = last.positions[i];
    ++counts[size_t(last.types[i])];
    if (last.types[i] == DiffuseType::Spray) {
      ASSERT_GT(p.x(), 1.5f) << "spray away from the jets";
    }
    if (last.types[i] == DiffuseType::Bubble) {
      ASSERT_LT(p.x(), 1.5f) << "a bubble at the jets";
    }
  }
  EXPECT_GT(counts[0], 10u);   // spray at the jet
  EXPECT_GT(counts[1], 10u);   // foam on the blocks' surfaces
  EXPECT_GT(counts[2], 100u);  // bubbles inside the impact
  // Emission happens at the impact: the first newborns lie near the plane where the blocks meet.
  const DiffuseFrame& first = r.frames[1];
  for (size_t i = 0; i < first.size(); ++i)
    if (first.positions[i].x() < 1.5f) {
      ASSERT_NEAR(first.positions[i].x(), 0.45f, 0.15f);
    }
}

TEST(DiffuseSimulator, FroudeScaledSceneEmitsAlikePerFluidParticle) {
  const int frames = 10;
  const auto small = colliding_blocks(frames, 1.0f), large = colliding_blocks(frames, 4.0f);
  const RunResult a = run(setup_for(1.0f), small), b = run(setup_for(4.0f), large);
  ASSERT_GT(a.generated, 1000u);
  const double per_particle_a = double(a.generated) / small[0].size();
  const double per_particle_b = double(b.generated) / large[0].size();
  EXPECT_NEAR(per_particle_b / per_particle_a, 1.0, 0.3);
}

TEST(DiffuseSimulator, SubstepsKeepTheMeanEmission) {
  const auto fluid = colliding_blocks(6);
  const RunResult one = run(setup_for(1.0f, 1), fluid), four = run(setup_for(1.0f, 4), fluid);
  // The potentials change within a frame as the blocks interpenetrate, so the totals differ by more
  // than the rounding noise; they must agree to within a modest fraction.
  EXPECT_NEAR(double(four.generated) / double(one.generated), 1.0, 0.25);
}

TEST(DiffuseSimulator, DiffuseParticlesNeverEnterSolidsAndLeaveTheDomainDeleted) {
  // Spray shot at a tank floor and into a sphere obstacle; the domain cuts off the far side.
  DiffuseSetup setup = setup_for(1.0f);
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(-1, 0, -1), tank.max = Vec3f(1, 1, 1);
  Solid ball;
  ball.kind = Solid::Kind::Sphere;
  ball.center = Vec3f(0.5f, 0.3f, 0.0f), ball.radius = 0.2f;
  setup.solids = SolidSet({tank, ball});
  setup.domain.min = Vec3f(-1, -0.1f, -1), setup.domain.max = Vec3f(1, 3, 1);
  setup.params.k_ta = setup.params.k_wc = 0.0f;
  DiffuseSimulator sim(setup);
  DiffuseFrame start;
  start.resize(3);
  start.positions = {Vec3f(0, 0.5f, 0), Vec3f(0.5f, 0.8f, 0), Vec3f(0.9f, 0.5f, 0)};
  start.velocities = {Vec3f(0, -30, 0), Vec3f(0, -10, 0), Vec3f(50, 0, 0)};
  start.lifetimes = {1, 1, 1};
  start.ids = {1, 2, 3};
  sim.set_particles(start);
  // A fluid far away, so nothing here has fluid neighbours: all three are spray.
  std::vector<FluidFrame> fluid;
  for (int k = 0; k < 20; ++k) fluid.push_back(testing::frame_of(k, k / 50.0, {Vec3f(5, 5, 5)}, {Vec3f::Zero()}));
  for (int k = 0; k + 1 < 20; ++k) {
    sim.process_frame(fluid[k], &fluid[k + 1], [](const DiffuseFrame&, const FrameStats&) {});
    for (const Vec3f& p : sim.particles().positions) {
      ASSERT_GE(p.y(), 0.0f);                                      // floor
      ASSERT_GE((p - ball.center).norm(), ball.radius * 0.9999f);  // sphere
      ASSERT_LE(std::abs(p.x()), 1.0f);                            // walls
    }
  }
  // The third particle hit the wall at x = 1 and stays; the others rest on the floor or the ball.
  EXPECT_EQ(sim.particles().size(), 3u);
  EXPECT_NEAR(sim.particles().positions[0].y(), 0.0f, 1e-3f);
}

TEST(DiffuseSimulator, WallsCountAsFluidSoABubbleAtTheFloorStaysABubble) {
  // A diffuse particle at the floor of a deep lattice pool sees about half the neighbours of the
  // interior (a half-sphere of fluid); counting the floor's share restores the interior count.
  const float r = 0.02f;
  const auto pool = testing::lattice(Vec3f(-0.3f, r, -0.3f), Vec3f(0.3f, 0.4f, 0.3f), 2 * r);
  std::vector<FluidFrame> fluid = {testing::frame_of(0, 0, pool, std::vector<Vec3f>(pool.size(), Vec3f::Zero()))};
  for (bool count_solids : {false, true}) {
    DiffuseSetup setup = setup_for(1.0f);
    setup.params.count_solids = count_solids;
    Solid tank;
    tank.kind = Solid::Kind::Tank;
    tank.min = Vec3f(-0.3f - r, 0, -0.3f - r), tank.max = Vec3f(0.3f + r, 1, 0.3f + r);
    setup.solids = SolidSet({tank});
    DiffuseSimulator sim(setup);
    DiffuseFrame d;
    d.resize(2);
    d.positions = {Vec3f(0.01f, 0.005f, 0.01f), Vec3f(0.01f, 0.2f, 0.01f)};  // at the floor; mid-depth
    d.velocities = {Vec3f::Zero(), Vec3f::Zero()};
    d.lifetimes = {1, 1};
    d.ids = {diffuse_id(0, 500, 0), diffuse_id(1, 500, 0)};
    sim.set_particles(d);
    DiffuseFrame out;
    sim.process_frame(fluid[0], nullptr, [&](const DiffuseFrame& f, const FrameStats&) { out = f; });
    EXPECT_EQ(out.types[1], DiffuseType::Bubble);  // (4/3) pi h^3 / (2r)^3 = 33.5 neighbours
    EXPECT_EQ(out.types[0], count_solids ? DiffuseType::Bubble : DiffuseType::Foam) << count_solids;
  }
}

TEST(DiffuseSimulator, AStepThatCannotFitIsRefusedWithTheNumbers) {
  // Room for 1,000 particles at the stage's bytes a particle: the collision makes more within a few
  // frames. The run stops at the step that would pass 1,000, and the frames before it are the ones an
  // unlimited run makes.
  const auto fluid = colliding_blocks(8);
  const RunResult unlimited = run(setup_for(1.0f), fluid);
  ASSERT_GT(unlimited.frames.back().size(), 2000u);
  DiffuseSetup setup = setup_for(1.0f);
  setup.available_memory = [] { return std::optional<double>(1000 * kDiffuseStageBytesPerParticle); };
  DiffuseSimulator sim(setup);
  std::vector<DiffuseFrame> frames;
  std::string message;
  try {
    for (size_t k = 0; k + 1 < fluid.size(); ++k)
      sim.process_frame(fluid[k], &fluid[k + 1], [&](const DiffuseFrame& f, const FrameStats&) { frames.push_back(f); });
  } catch (const Error& e) {
    message = e.what();
  }
  ASSERT_FALSE(message.empty()) << "never refused";
  EXPECT_NE(message.find("the diffuse stage cannot hold"), std::string::npos) << message;
  EXPECT_NE(message.find("diffuse.max_particles"), std::string::npos) << message;
  EXPECT_EQ(message.find("the diffuse stage"), 0u) << message;  // the caller names the frame
  ASSERT_FALSE(frames.empty());
  for (size_t k = 0; k < frames.size(); ++k) {
    EXPECT_LE(frames[k].size(), 1000u) << k;
    EXPECT_TRUE(same_bytes(frames[k].ids, unlimited.frames[k].ids)) << k;
  }
}

}  // namespace
}  // namespace spume
