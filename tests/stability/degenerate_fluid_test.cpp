// Degenerate fluids: every particle at one point, a single particle, no particle at all, and frames
// holding NaN or Inf (refused by every reader with the particle's index and the file named).
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "sim/io/bgeo.h"
#include "sim/io/particle_file.h"
#include "sim/io/ply.h"
#include "sim/io/spume_cache.h"
#include "sim/io/vtk.h"
#include "tests/stability/bad_files.h"
#include "tests/stability/stability_support.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using stability::error_of;

const Vec3f kG(0, -9.81f, 0);

// The exact ballistic position after time t from x0 with v0 (the spray's closed form).
Vec3f parabola(const Vec3f& x0, const Vec3f& v0, float t) { return x0 + t * v0 + (0.5f * t * t) * kG; }

TEST(StabilityDegenerate, AllFluidParticlesAtOnePoint) {
  // 500 particles at the origin, at rest and then with random velocities (trapped air between
  // particles with no distance between them): the guards of MODEL.md §8 keep every value finite.
  for (bool moving : {false, true}) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-3.0f, 3.0f);
    std::vector<Vec3f> x(500, Vec3f(0.1f, 0.2f, 0.3f)), v(500, Vec3f::Zero());
    if (moving)
      for (auto& w : v) w = Vec3f(u(rng), u(rng), u(rng));
    std::vector<FluidFrame> fluid;
    for (int k = 0; k < 4; ++k) {
      // Frames all coincident too (the particles do not actually move apart): a pile that stays a pile.
      fluid.push_back(testing::frame_of(k, k / 50.0, x, v));
    }
    DiffuseSetup setup = stability::setup_with(0.02f);
    setup.domain.min = Vec3f(-1, -1, -1), setup.domain.max = Vec3f(1, 1, 1);
    DiffuseSimulator sim(setup);
    // At the pile: 500 neighbours (a bubble); 3 h away: none (spray).
    sim.set_particles(stability::diffuse_at({Vec3f(0.1f, 0.2f, 0.3f), Vec3f(0.1f, 0.2f + 0.24f, 0.3f)},
                                            DiffuseType::Foam));
    std::vector<DiffuseType> first_types;
    for (size_t k = 0; k < fluid.size(); ++k)
      sim.process_frame(fluid[k], k + 1 < fluid.size() ? &fluid[k + 1] : nullptr,
                        [&](const DiffuseFrame& f, const FrameStats&) {
                          EXPECT_TRUE(stability::all_finite(f));
                          if (k == 0) first_types = f.types;
                        });
    ASSERT_EQ(first_types.size(), 2u);
    EXPECT_EQ(first_types[0], DiffuseType::Bubble);
    EXPECT_EQ(first_types[1], DiffuseType::Spray);
    EXPECT_TRUE(stability::all_finite(sim.particles()));
  }
}

TEST(StabilityDegenerate, SingleFluidParticleEmitsNothingAndSprayFallsOnItsParabola) {
  // One particle has no neighbours: no trapped air (Eq. 2 sums over neighbours), no crest (no
  // normal, Eq. 4): n_d = 0 whatever its energy. A diffuse particle near it sees one neighbour: spray.
  std::vector<FluidFrame> fluid;
  const Vec3f vf(3, 1, 0);
  for (int k = 0; k < 6; ++k) fluid.push_back(testing::frame_of(k, k / 50.0, {float(k / 50.0) * vf}, {vf}));
  DiffuseSetup setup = stability::setup_with(0.02f);
  DiffuseSimulator sim(setup);
  const Vec3f x0(0.01f, 0.0f, 0.0f), v0(0.5f, 2.0f, 0.0f);
  sim.set_particles(stability::diffuse_at({x0}, DiffuseType::Foam, v0));
  const auto run = stability::run_checked(sim, fluid, true);
  EXPECT_EQ(run.generated, 0u);
  ASSERT_EQ(run.frames.size(), fluid.size());
  for (size_t k = 0; k < run.frames.size(); ++k) {
    ASSERT_EQ(run.frames[k].size(), 1u);
    EXPECT_EQ(run.frames[k].types[0], DiffuseType::Spray) << k;
    EXPECT_LT((run.frames[k].positions[0] - parabola(x0, v0, float(k / 50.0))).norm(), 1e-5f) << k;
  }
}

TEST(StabilityDegenerate, EmptyFramesLeaveOnlySpray) {
  // No fluid at all (the first frame, the last, and both): diffuse particles of every type have no
  // neighbours, become spray and fly their parabolas; nothing is emitted. (A translating block traps no
  // air, but its leading edges are crests moving along their normals, MODEL.md §8.10: crest emission is
  // off here so that the three particles are all there is.)
  FluidFrame empty0 = testing::frame_of(0, 0.0, {}, {}), empty1 = testing::frame_of(1, 0.02, {}, {});
  const auto block = stability::translating_block(Vec3f(2, 2, 2), Vec3f(2.2f, 2.2f, 2.2f), 0.02f, Vec3f(1, 0, 0),
                                                  0.02, 2);
  const Vec3f x0(0, 1, 0), v0(1, 0, 0);
  const std::vector<std::pair<const FluidFrame*, const FluidFrame*>> pairs = {
      {&empty0, &empty1}, {&empty0, &block[1]}, {&block[0], &empty1}, {&empty0, nullptr}};
  for (const auto& [a, b] : pairs) {
    DiffuseSimulator sim(stability::setup_with(0.02f, {{"k_wc", 0}}));
    sim.set_particles(stability::diffuse_at({x0, x0, x0}, DiffuseType::Bubble, v0));
    sim.particles();
    DiffuseFrame d = sim.particles();
    d.types = {DiffuseType::Spray, DiffuseType::Foam, DiffuseType::Bubble};
    d.ids = {diffuse_id(0, 500, 0), diffuse_id(1, 500, 0), diffuse_id(2, 500, 0)};
    sim.set_particles(d);
    const FrameStats s = sim.process_frame(*a, b, [](const DiffuseFrame& f, const FrameStats&) {
      EXPECT_TRUE(stability::all_finite(f));
      for (DiffuseType t : f.types) EXPECT_EQ(t, DiffuseType::Spray);
    });
    EXPECT_EQ(s.fluid, a->size());
    EXPECT_TRUE(stability::all_finite(sim.particles()));
    ASSERT_EQ(sim.particles().size(), 3u);
    if (b) {
      for (const Vec3f& x : sim.particles().positions) EXPECT_LT((x - parabola(x0, v0, 0.02f)).norm(), 1e-5f);
    }
  }
}

// A frame of 20 particles with one bad value at particle 7, in every format spume reads: the writers
// refuse such a frame, so the files are spoiled after writing (bad_files.h).
struct BadValue {
  const char* what;
  float value;
  bool in_velocity;
};

TEST(StabilityDegenerate, NonFiniteValuesAreRefusedNamingFileAndParticle) {
  const testing::TempDir temp;
  const std::filesystem::path& dir = temp.path;
  const BadValue bad[] = {{"nan position", NAN, false}, {"inf position", INFINITY, false},
                          {"nan velocity", NAN, true}, {"-inf velocity", -INFINITY, true}};
  for (const BadValue& b : bad) {
    std::vector<Vec3f> x, v;
    for (int i = 0; i < 20; ++i) x.push_back(Vec3f(0.04f * i, 0, 0)), v.push_back(Vec3f(1, 0, 0));
    FluidFrame frame = testing::frame_of(0, 0.0, x, v);
    (b.in_velocity ? frame.velocities : frame.positions)[7].y() = b.value;
    // In memory, the frame's own check; the writers run it too.
    const std::string m = error_of([&] { frame.validate("frame 0"); });
    EXPECT_NE(m.find("particle 7"), std::string::npos) << b.what << ": " << m;
    EXPECT_NE(error_of([&] { write_ply(dir / "refused.ply", frame); }).find("particle 7"), std::string::npos);
    (b.in_velocity ? frame.velocities : frame.positions)[7].y() = stability::kMarker;
    struct Format {
      std::string name;
      std::function<void(const fs::path&)> write;
      bool big_endian, crc;
    };
    const Format formats[] = {
        {"bad.bgeo", [&](const fs::path& p) { write_bgeo(p, frame); }, true, false},
        {"bad.vtk", [&](const fs::path& p) { write_vtk(p, frame); }, true, false},
        {"bad.ply", [&](const fs::path& p) { write_ply(p, frame); }, false, false},
        {"bad.spf", [&](const fs::path& p) { write_fluid_cache(p, frame, 0.02f); }, false, true},
    };
    for (const Format& f : formats) {
      const fs::path path = dir / f.name;
      f.write(path);
      stability::spoil_marker(path, b.value, f.big_endian, f.crc);
      const std::string message = error_of([&] { read_fluid_file(path); });
      EXPECT_NE(message.find("particle 7"), std::string::npos) << b.what << ", " << f.name << ": " << message;
      EXPECT_NE(message.find(path.string()), std::string::npos) << b.what << ", " << f.name << ": " << message;
    }
  }
}

}  // namespace
}  // namespace spume
