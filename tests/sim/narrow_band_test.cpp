// Narrow-band caches (MODEL.md §9.1): a block of water whose particles fill only a band under its
// surface must classify its interior as a full block does, and a full block must be left as it was.
#include <gtest/gtest.h>

#include <cmath>

#include <cstring>
#include <random>

#include "sim/core/parallel.h"
#include "sim/diffuse/simulator.h"
#include "sim/scene/diffuse_params_reader.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

constexpr float kR = 0.02f, kS = 2 * kR, kH = 4 * kR;  // radius, spacing, support radius (h = 2 spacings)
constexpr float kSide = 31 * kS;                         // a cube of 32 particles a side

DiffuseSetup setup_with(bool fill, FluidParticles particles = FluidParticles::Sph) {
  DiffuseSetup s;
  s.fluid.particle_radius = kR;
  s.fluid.support_radius = kH;
  s.params = read_diffuse_params(ParamReader::from_json(Json::object(), "test"), s.fluid, Vec3f(0, -9.81f, 0));
  s.fill_narrow_band = fill;
  s.particles = particles;
  return s;
}

// The lattice cube, or only its particles within `band` of the top and side faces (and of the
// bottom face too unless `open_floor`: Mantaflow keeps no band along a floor, which is no surface).
std::vector<Vec3f> cube(float band, bool open_floor) {
  std::vector<Vec3f> out;
  for (const Vec3f& p : testing::lattice(Vec3f::Zero(), Vec3f::Constant(kSide), kS)) {
    float depth = std::min({p.x(), kSide - p.x(), kSide - p.y(), p.z(), kSide - p.z()});
    if (!open_floor) depth = std::min(depth, p.y());
    if (depth < band) out.push_back(p);
  }
  return out;
}

// Probes inside the cube, on a lattice shifted by half a spacing (no fluid particle lies exactly at
// h from one), at least 2h from every face: their h-sphere lies in the water.
std::vector<Vec3f> interior_probes() {
  std::vector<Vec3f> p;
  for (float z = 2 * kH + 0.5f * kS; z < kSide - 2 * kH; z += 3 * kS)
    for (float y = 2 * kH + 0.5f * kS; y < kSide - 2 * kH; y += 3 * kS)
      for (float x = 2 * kH + 0.5f * kS; x < kSide - 2 * kH; x += 3 * kS) p.emplace_back(x, y, z);
  return p;
}

// Types of `probes` classified against `fluid` (one frame, classification only; probes are newborn,
// so no hysteresis), in probe order.
std::vector<DiffuseType> classify_probes(const std::vector<Vec3f>& fluid, const std::vector<Vec3f>& probes, bool fill,
                                         FrameStats* stats = nullptr, FluidParticles particles = FluidParticles::Sph) {
  DiffuseSimulator sim(setup_with(fill, particles));
  DiffuseFrame d;
  d.resize(probes.size());
  for (uint32_t i = 0; i < probes.size(); ++i) {
    d.ids[i] = diffuse_id(i, kMaxBirthStep, 0);  // born in the step before step 0: newborn
    d.positions[i] = probes[i];
    d.velocities[i] = Vec3f::Zero();
    d.lifetimes[i] = 1.0f;
    d.types[i] = DiffuseType::Spray;
  }
  sim.set_particles(d);
  std::vector<DiffuseType> types(probes.size());
  const FluidFrame frame = testing::frame_of(0, 0.0, fluid, std::vector<Vec3f>(fluid.size(), Vec3f::Zero()));
  const FrameStats s = sim.process_frame(frame, nullptr, [&](const DiffuseFrame& f, const FrameStats&) {
    for (size_t k = 0; k < f.size(); ++k) types[diffuse_id_parent(f.ids[k])] = f.types[k];
  });
  if (stats) *stats = s;
  return types;
}

TEST(NarrowBand, HollowAndFullBlockClassifyTheirInteriorAlike) {
  // By hand: a probe whose h-sphere lies in water at spacing h/2 counts about 4/3 pi 2^3 = 33.5
  // particles, above the bubble limit of 20: a bubble. Without filling, the hollow cube's interior
  // probes more than h inside the band count nothing: spray.
  const auto probes = interior_probes();
  ASSERT_GE(probes.size(), 27u);
  const auto full = classify_probes(cube(1e9f, false), probes, true);
  for (size_t k = 0; k < probes.size(); ++k) ASSERT_EQ(full[k], DiffuseType::Bubble) << k;
  for (const bool open_floor : {false, true}) {
    SCOPED_TRACE(open_floor ? "band open at the floor" : "band on every face");
    const auto hollow = cube(3 * kH, open_floor);  // a band of three h (Mantaflow: 3 cells of about h)
    FrameStats stats;
    // A FLIP cache (a narrow band is filled only there); on a lattice its measured density is the nominal.
    const auto filled = classify_probes(hollow, probes, true, &stats, FluidParticles::Flip);
    EXPECT_TRUE(stats.interior.narrow_band) << describe_interior(stats.interior);
    EXPECT_GT(stats.interior.filled, 0u);
    for (size_t k = 0; k < probes.size(); ++k) EXPECT_EQ(filled[k], full[k]) << probes[k].transpose() / kS;
    // The same cache taken as it is (fluid.narrow_band = off): the deep interior is spray.
    const auto as_is = classify_probes(hollow, probes, false, nullptr, FluidParticles::Flip);
    size_t centre = 0;
    for (size_t k = 0; k < probes.size(); ++k)
      if ((probes[k] - Vec3f::Constant(kSide / 2)).norm() < (probes[centre] - Vec3f::Constant(kSide / 2)).norm()) centre = k;
    EXPECT_EQ(as_is[centre], DiffuseType::Spray);
  }
}

TEST(NarrowBand, FullBlockAndSmallAirPocketAreLeftAsTheyAre) {
  auto full = cube(1e9f, false);
  testing::jitter(full, 0.2f * kS, 7);
  // A pocket of 2 x 2 x 2 h (64 particles) of air in a cube of 32^3: enclosed, but below 5% of the water.
  std::vector<Vec3f> pocket;
  for (const Vec3f& p : full)
    if ((p - Vec3f::Constant(kSide / 2)).cwiseAbs().maxCoeff() > kH) pocket.push_back(p);
  for (const auto* fluid : {&full, &pocket}) {
    for (const bool flip : {false, true}) {
      InteriorFiller filler;
      const InteriorFill fill = filler.examine(*fluid, kH, Vec3f(0, -9.81f, 0), flip);
      EXPECT_FALSE(fill.large);
      EXPECT_FALSE(fill.narrow_band);
      if (fluid == &pocket) {
        EXPECT_GT(fill.enclosed_cells, 0u);  // seen, and judged too small to be a band
      }
    }
    // Through a run: nothing is added to the fluid.
    FrameStats stats;
    classify_probes(*fluid, interior_probes(), true, &stats);
    EXPECT_FALSE(stats.interior.narrow_band);
    EXPECT_EQ(stats.interior.filled, 0u);
  }
}

// Gaps of a cell between a band's particles do not open it to the air. The hollow cube's top band has
// a vertical channel through it, 3 x 3 particle columns wide: 4 spacings (2 h) between the particles on
// either side, so whatever the cells' offset a full cell lies in it on both axes across, and the channel
// is a column of empty cells from the air to the interior. Each of those cells lies within h / 2 (one
// spacing) of a particle beside the channel (by hand: a cell of h in a gap of 2 h ends at most h / 2
// from its sides), so each is sealed: the interior stays enclosed, as a FLIP cache's band with a few
// empty cells left by random seeding does.
TEST(NarrowBand, AChannelOfEmptyCellsThroughTheBandDoesNotOpenIt) {
  const int mid = 16;  // lattice index of the channel's middle column (the cube is 32 particles a side)
  std::vector<Vec3f> band;
  for (const Vec3f& p : cube(3 * kH, true)) {
    const int i = int(std::lround(p.x() / kS)), k = int(std::lround(p.z() / kS));
    const bool in_channel = std::abs(i - mid) <= 1 && std::abs(k - mid) <= 1 && p.y() > kSide - 3 * kH;
    if (!in_channel) band.push_back(p);
  }
  InteriorFiller filler;
  const InteriorFill fill = filler.examine(band, kH, Vec3f(0, -9.81f, 0), true);
  EXPECT_TRUE(fill.large) << describe_interior(fill);
  EXPECT_TRUE(fill.narrow_band) << describe_interior(fill);
  // The enclosed cells: the interior inside the band, 31 - 2 x 6 = 19 spacings (9.5 h) a side, so at
  // least 8 whole cells a side: over 8^3 = 512. Opened to the air, none would be.
  EXPECT_GT(fill.enclosed_cells, 512u) << describe_interior(fill);
}

// The SPH block (r = 0.02, 1.2 x 0.8 x 0.8 m on a 2r lattice) with a spherical void of radius
// 0.26 m about its centre: enclosed and large (the void is 9.6% of the block's volume), measured 0.14
// to 0.34 m under the surface by hand (2 to 4 cells of h = 0.08 m), and air unless the cache is FLIP.
TEST(NarrowBand, AnEnclosedInteriorIsABandOnlyInAFlipCache) {
  const Vec3f size(1.2f, 0.8f, 0.8f), centre = size / 2;
  std::vector<Vec3f> void_block;
  for (const Vec3f& p : testing::lattice(Vec3f::Constant(kR), size - Vec3f::Constant(kR), kS))
    if ((p - centre).norm() > 0.26f) void_block.push_back(p);
  InteriorFiller filler;
  const InteriorFill pocket = filler.examine(void_block, kH, Vec3f(0, -9.81f, 0), false);
  EXPECT_TRUE(pocket.large) << pocket.enclosed_cells << " of " << pocket.occupied_cells;
  EXPECT_FALSE(pocket.narrow_band);
  // The edge's depth, to within a cell of the hand-worked 0.14 and 0.34 m.
  EXPECT_NEAR(pocket.depth_low, 0.14f, kH);
  EXPECT_NEAR(pocket.depth_high, 0.34f, kH);
  EXPECT_EQ(describe_interior(pocket).rfind("ENCLOSED, not filled: ", 0), 0u) << describe_interior(pocket);
  const InteriorFill flip = filler.examine(void_block, kH, Vec3f(0, -9.81f, 0), true);
  EXPECT_TRUE(flip.narrow_band);  // a FLIP source: its enclosed interior is the band's

  // Through a run (SPH): the block is left as it was.
  FrameStats stats;
  classify_probes(void_block, {centre}, true, &stats);
  EXPECT_TRUE(stats.interior.large);
  EXPECT_FALSE(stats.interior.narrow_band);
  EXPECT_EQ(stats.interior.filled, 0u);
}

TEST(NarrowBand, FilledInteriorMovesWithTheBand) {
  // A hollow cube translating at u: the filling carries u (the mean of identical values), so
  // bubbles inside are dragged along with the water.
  const Vec3f u(1.0f, 0.0f, -0.5f);
  const auto hollow = cube(3 * kH, true);
  FluidStepState state = testing::state_of(hollow, std::vector<Vec3f>(hollow.size(), u));
  InteriorFiller filler;
  ASSERT_TRUE(filler.examine(state.positions, kH, Vec3f(0, -9.81f, 0), true).narrow_band);
  const size_t filled = filler.fill(state, kH, kS, Vec3f(0, -9.81f, 0), nullptr);
  ASSERT_GT(filled, 0u);
  ASSERT_EQ(state.positions.size(), hollow.size() + filled);
  for (size_t i = hollow.size(); i < state.positions.size(); ++i) {
    ASSERT_EQ(state.velocities[i], u) << i;
    ASSERT_EQ(state.motion[i], u) << i;
    ASSERT_EQ(state.masses[i], 0.0f) << i;  // emits nothing
    ASSERT_EQ(state.ids[i], kFillerId);
  }
  // Every filler lies inside the cube, at least a spacing from every band particle.
  for (size_t i = hollow.size(); i < state.positions.size(); ++i) {
    const Vec3f& p = state.positions[i];
    ASSERT_TRUE((p.array() > 0.0f).all() && (p.array() < kSide).all()) << p.transpose();
  }
}

}  // namespace
}  // namespace spume

namespace spume {
namespace {

TEST(NarrowBand, FlipAndFillAreByteIdenticalForOneAndTwoThreads) {
  // A hollow cube (open at the floor) sliding at 2 m/s with noisy velocities, as FLIP: emission,
  // filling and classification over two frames must not depend on the thread count.
  auto x = cube(3 * kH, true);
  testing::jitter(x, 0.1f * kS, 9);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> noise(-0.5f, 0.5f);
  std::vector<Vec3f> v(x.size());
  for (Vec3f& vi : v) vi = Vec3f(2.0f + noise(rng), noise(rng), noise(rng));
  std::vector<Vec3f> x1 = x;
  for (size_t i = 0; i < x1.size(); ++i) x1[i] += 0.02f * v[i];
  const FluidFrame a = testing::frame_of(0, 0.0, x, v), b = testing::frame_of(1, 0.02, x1, v),
                   c = testing::frame_of(2, 0.04, x1, v);
  auto run = [&](int threads) {
    set_thread_count(threads);
    DiffuseSetup setup = setup_with(true);
    setup.particles = FluidParticles::Flip;
    setup.params.substeps = 2;
    DiffuseSimulator sim(setup);
    DiffuseFrame last;
    sim.process_frame(a, &b, [](const DiffuseFrame&, const FrameStats&) {});
    sim.process_frame(b, &c, [](const DiffuseFrame&, const FrameStats&) {});
    sim.process_frame(c, nullptr, [&](const DiffuseFrame& f, const FrameStats&) { last = f; });
    set_thread_count(0);
    return last;
  };
  const DiffuseFrame one = run(1), two = run(2);
  ASSERT_GT(one.size(), 0u);
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.positions.data(), two.positions.data(), one.size() * sizeof(Vec3f)), 0);
  EXPECT_EQ(std::memcmp(one.velocities.data(), two.velocities.data(), one.size() * sizeof(Vec3f)), 0);
  EXPECT_EQ(one.ids, two.ids);
  EXPECT_EQ(one.types, two.types);
}

}  // namespace
}  // namespace spume
