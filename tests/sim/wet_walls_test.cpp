// Walls count only where they are wet (MODEL.md §8.10-11): classification, the surface test and
// advection next to solids, on a resting pool in a tank worked out by hand.
#include <gtest/gtest.h>

#include <numbers>

#include "sim/diffuse/potentials.h"
#include "sim/diffuse/simulator.h"
#include "sim/geometry/solid_coverage.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

// A tank [0,1]^3 holding a resting pool 0.3 m deep: r = 0.02 m, lattice of spacing 2r from r off
// each wall, h = 4r. A full neighbourhood holds 4/3 pi h^3 / (2r)^3 = 33.5 particles.
constexpr float kR = 0.02f, kH = 0.08f, kDepth = 0.3f;
const float kFull = 4.0f / 3.0f * std::numbers::pi_v<float> * 8.0f;

std::vector<Vec3f> pool() { return testing::lattice(Vec3f(kR, kR, kR), Vec3f(1 - kR, kDepth, 1 - kR), 2 * kR); }

SolidSet tank(bool open_top = true) {
  Solid s;
  s.kind = Solid::Kind::Tank;
  s.min = Vec3f::Zero(), s.max = Vec3f::Ones(), s.open_top = open_top;
  return SolidSet({s});
}

// The neighbour count classification uses: fluid within h by brute force, then the wet-wall scaling.
float effective_count(const std::vector<Vec3f>& fluid, const SolidSet& solids, const Vec3f& p) {
  float n = 0;
  for (const Vec3f& f : fluid) n += (f - p).squaredNorm() <= kH * kH;
  return wet_wall_count(n, solid_coverage(solids, p, kH, false).fraction);
}

// What a wet wall stands for: the fluid mirrored across the wall planes x = 0 and y = 0 (as `axes`
// says), counted like any fluid.
float mirrored_count(const std::vector<Vec3f>& fluid, const Vec3f& p, bool mirror_x, bool mirror_y) {
  float n = 0;
  for (const Vec3f& f : fluid)
    for (int mx = 0; mx <= int(mirror_x); ++mx)
      for (int my = 0; my <= int(mirror_y); ++my) {
        const Vec3f g(mx ? -f.x() : f.x(), my ? -f.y() : f.y(), f.z());
        n += (g - p).squaredNorm() <= kH * kH;
      }
  return n;
}

TEST(WetWalls, DryWallAddsNothingWaterlineAboutHalfSubmergedFloorAFullShare) {
  const auto fluid = pool();
  const SolidSet solids = tank();
  EXPECT_EQ(effective_count(fluid, solids, {0.001f, 0.7f, 0.5f}), 0.0f);    // dry wall
  EXPECT_EQ(effective_count(fluid, solids, {0.001f, 0.7f, 0.001f}), 0.0f);  // dry edge
  // Submerged floor and edge: what the same point counts with water beyond the walls (the lattice
  // itself makes that 28 here, against 33.5 on average).
  const Vec3f floor(0.5f, 0.001f, 0.5f), edge(0.001f, 0.001f, 0.5f);
  EXPECT_NEAR(effective_count(fluid, solids, floor), mirrored_count(fluid, floor, false, true), 0.05f * kFull);
  EXPECT_NEAR(effective_count(fluid, solids, edge), mirrored_count(fluid, edge, true, true), 0.05f * kFull);
  // Waterline: water beyond the wall only below the surface, so about half a neighbourhood.
  const Vec3f waterline(0.001f, kDepth + kR, 0.5f);
  const float at_waterline = effective_count(fluid, solids, waterline);
  EXPECT_NEAR(at_waterline, mirrored_count(fluid, waterline, true, false), 0.05f * kFull);
  EXPECT_NEAR(at_waterline, 0.5f * kFull, 0.2f * kFull);
}

DiffuseSetup setup(const SolidSet& solids) {
  DiffuseSetup s;
  s.fluid.particle_radius = kR;
  s.fluid.support_radius = kH;
  s.fluid.fps = 50.0;
  s.solids = solids;
  s.params.k_ta = s.params.k_wc = 0.0f;  // nothing is born: only the particles placed by hand
  return s;
}

DiffuseFrame placed(const std::vector<Vec3f>& positions, const std::vector<Vec3f>& velocities) {
  DiffuseFrame d;
  d.resize(positions.size());
  for (size_t i = 0; i < positions.size(); ++i) {
    d.ids[i] = diffuse_id(uint32_t(i), 5, 0);  // born long ago: hysteresis applies
    d.positions[i] = positions[i];
    d.velocities[i] = velocities[i];
    d.lifetimes[i] = 2.0f;
    d.types[i] = DiffuseType::Foam;  // what a dry wall used to make of them
  }
  return d;
}

TEST(WetWalls, DryEdgesAndCornersAreSprayNotBubbles) {
  const SolidSet solids = tank(false);
  DiffuseSimulator sim(setup(solids));
  const std::vector<Vec3f> at = {{0.001f, 0.7f, 0.5f},      // dry wall
                                 {0.001f, 0.7f, 0.001f},    // dry vertical edge
                                 {0.5f, 0.999f, 0.001f},    // dry edge under the lid
                                 {0.001f, 0.999f, 0.001f},  // dry corner under the lid
                                 {0.5f, 0.001f, 0.5f},      // submerged floor
                                 {0.001f, 0.001f, 0.001f},  // submerged corner
                                 {0.5f, kDepth + kR, 0.001f}};  // waterline
  sim.set_particles(placed(at, std::vector<Vec3f>(at.size(), Vec3f::Zero())));
  const FluidFrame fluid = testing::frame_of(0, 0.0, pool(), std::vector<Vec3f>(pool().size(), Vec3f::Zero()));
  std::vector<DiffuseType> types;
  sim.process_frame(fluid, nullptr, [&](const DiffuseFrame& f, const FrameStats&) { types = f.types; });
  ASSERT_EQ(types.size(), at.size());
  for (int i = 0; i < 4; ++i) EXPECT_EQ(types[size_t(i)], DiffuseType::Spray) << i;
  EXPECT_EQ(types[4], DiffuseType::Bubble);
  EXPECT_EQ(types[5], DiffuseType::Bubble);
  EXPECT_EQ(types[6], DiffuseType::Foam);
}

TEST(WetWalls, SprayThrownAtADryWallStaysSprayAndFalls) {
  const SolidSet solids = tank();
  DiffuseSimulator sim(setup(solids));
  sim.set_particles(placed({{0.2f, 0.8f, 0.5f}}, {{-3.0f, 0.0f, 0.0f}}));
  const auto fluid = pool();
  const std::vector<Vec3f> still(fluid.size(), Vec3f::Zero());
  std::vector<DiffuseFrame> out;
  const int frames = 11;  // 0.2 s: it reaches the wall after 0.067 s
  std::vector<FluidFrame> seq;
  for (int k = 0; k < frames; ++k) seq.push_back(testing::frame_of(k, k / 50.0, fluid, still));
  for (int k = 0; k < frames; ++k)
    sim.process_frame(seq[size_t(k)], k + 1 < frames ? &seq[size_t(k) + 1] : nullptr,
                      [&](const DiffuseFrame& f, const FrameStats&) { out.push_back(f); });
  for (int k = 1; k < frames; ++k) {
    ASSERT_EQ(out[size_t(k)].size(), 1u);
    EXPECT_EQ(out[size_t(k)].types[0], DiffuseType::Spray) << k;
    EXPECT_GE(out[size_t(k)].positions[0].x(), 0.0f);
  }
  // Free fall for 0.2 s: 0.8 - g t^2 / 2 = 0.604 m, its wall contact notwithstanding.
  EXPECT_NEAR(out.back().positions[0].y(), 0.8f - 0.5f * 9.81f * 0.04f, 1e-3f);
  EXPECT_NEAR(out.back().positions[0].x(), 0.0f, 1e-3f);
}

TEST(WetWalls, SprayOverTheRimFallsOutsideTheTankNotBackThroughItsWall) {
  // Walls 0.16 m thick (2 h): a particle 0.12 m beyond the x = 0 wall, above the rim at y = 1, falls
  // past the rim into the wall's outer half and leaves by its outer face.
  SolidSet solids = tank();
  std::vector<Solid> with_walls = solids.solids();
  with_walls[0].wall_thickness = 2 * kH;
  DiffuseSimulator sim(setup(SolidSet(with_walls)));
  sim.set_particles(placed({{-0.12f, 1.05f, 0.5f}}, {{0.0f, 0.0f, 0.0f}}));
  const auto fluid = pool();
  const std::vector<Vec3f> still(fluid.size(), Vec3f::Zero());
  std::vector<FluidFrame> seq;
  for (int k = 0; k < 11; ++k) seq.push_back(testing::frame_of(k, k / 50.0, fluid, still));
  for (int k = 0; k + 1 < 11; ++k) sim.process_frame(seq[size_t(k)], &seq[size_t(k) + 1], [](const DiffuseFrame&, const FrameStats&) {});
  ASSERT_EQ(sim.particles().size(), 1u);
  const Vec3f x = sim.particles().positions[0];
  EXPECT_LT(x.x(), -2 * kH);                                   // outside the wall, not inside the tank
  EXPECT_NEAR(x.y(), 1.05f - 0.5f * 9.81f * 0.04f, 1e-3f);    // in free fall all along
}

TEST(WetWalls, AStepLongerThanTheWallIsThickStopsAtItsInnerFace) {
  // Walls 0.16 m thick; steps of 0.4 m cross them whole. Hand-worked crossings of the tank [0,1]^3.
  std::vector<Solid> walls = tank().solids();
  walls[0].wall_thickness = 2 * kH;
  const SolidSet solids(walls);
  const float skin = 1e-4f;
  // Through the x = 1 wall at mid height: ends at its inner face, the velocity into it removed.
  Vec3f p(1.3f, 0.5f, 0.5f), v(20.0f, -1.0f, 0.0f);
  EXPECT_TRUE(solids.stop_at_tank_walls(Vec3f(0.9f, 0.5f, 0.5f), p, v, skin));
  EXPECT_FLOAT_EQ(p.x(), 1.0f - skin);
  EXPECT_FLOAT_EQ(p.y(), 0.5f);
  EXPECT_EQ(v, Vec3f(0.0f, -1.0f, 0.0f));
  // Through the floor: ends on it.
  p = Vec3f(0.5f, -0.3f, 0.4f), v = Vec3f(0.0f, -10.0f, 1.0f);
  EXPECT_TRUE(solids.stop_at_tank_walls(Vec3f(0.5f, 0.1f, 0.4f), p, v, skin));
  EXPECT_FLOAT_EQ(p.y(), skin);
  EXPECT_EQ(v, Vec3f(0.0f, 0.0f, 1.0f));
  // Crossing the plane x = 1 above the open rim (at y = 0.98 + 0.2 * 0.12 = 1.004): over the wall.
  p = Vec3f(1.2f, 1.1f, 0.5f), v = Vec3f(10.0f, 6.0f, 0.0f);
  EXPECT_FALSE(solids.stop_at_tank_walls(Vec3f(0.95f, 0.98f, 0.5f), p, v, skin));
  EXPECT_EQ(p, Vec3f(1.2f, 1.1f, 0.5f));
  // Moving away from a wall, or staying inside: untouched.
  p = Vec3f(0.5f, 0.5f, 0.5f), v = Vec3f(-1.0f, 0.0f, 0.0f);
  EXPECT_FALSE(solids.stop_at_tank_walls(Vec3f(0.6f, 0.5f, 0.5f), p, v, skin));
  EXPECT_EQ(p, Vec3f(0.5f, 0.5f, 0.5f));
}

TEST(WetWalls, FastSprayAtAWallStaysInTheTank) {
  // 20 m/s at the x = 0 wall (0.16 m thick): one 0.02 s step would carry it 0.4 m, through the wall and
  // out of the tank's domain; it stops at the wall and falls along it.
  std::vector<Solid> walls = tank().solids();
  walls[0].wall_thickness = 2 * kH;
  DiffuseSetup s = setup(SolidSet(walls));
  s.domain = Aabb{Vec3f::Zero(), Vec3f(1.0f, 2.0f, 1.0f)};
  DiffuseSimulator sim(s);
  sim.set_particles(placed({{0.2f, 0.8f, 0.5f}}, {{-20.0f, 0.0f, 0.0f}}));
  const auto fluid = pool();
  const std::vector<Vec3f> still(fluid.size(), Vec3f::Zero());
  std::vector<FluidFrame> seq;
  for (int k = 0; k < 6; ++k) seq.push_back(testing::frame_of(k, k / 50.0, fluid, still));
  for (int k = 0; k + 1 < 6; ++k) sim.process_frame(seq[size_t(k)], &seq[size_t(k) + 1], [](const DiffuseFrame&, const FrameStats&) {});
  ASSERT_EQ(sim.particles().size(), 1u) << "lost through the wall";
  const Vec3f x = sim.particles().positions[0];
  EXPECT_NEAR(x.x(), 0.0f, 1e-3f);
  EXPECT_NEAR(x.y(), 0.8f - 0.5f * 9.81f * 0.01f, 1e-3f);  // 0.1 s of free fall along the wall
}

TEST(WetWalls, TheLayerAgainstAWallIsInteriorAndTheWaterlineFacesUp) {
  const auto fluid = pool();
  const auto state = testing::state_of(fluid, std::vector<Vec3f>(fluid.size(), Vec3f::Zero()));
  NeighbourGrid grid;
  grid.build(state.positions, kH);
  DiffuseParams params;
  const SolidSet solids = tank();
  std::vector<Vec3f> with_walls, without;
  compute_normals(grid, 8 * kR * kR * kR, params, &solids, with_walls);
  compute_normals(grid, 8 * kR * kR * kR, params, nullptr, without);
  int wall_layer = 0, blind_surface = 0, waterline = 0;
  for (size_t i = 0; i < fluid.size(); ++i) {
    const Vec3f& p = fluid[i];
    const bool at_wall = p.x() < 2 * kR || p.z() < 2 * kR || p.y() < 2 * kR;
    const bool top = p.y() > kDepth - kR;
    if (at_wall && !top && p.y() < kDepth - 3 * kR) {
      ++wall_layer;
      blind_surface += without[i].squaredNorm() > 0;  // without walls the layer looks like a surface
      EXPECT_EQ(with_walls[i], Vec3f::Zero()) << p.transpose();
    }
    if (top) {
      ASSERT_GT(with_walls[i].squaredNorm(), 0) << p.transpose();
      const int walls = (p.x() < 2 * kR || p.x() > 1 - 2 * kR) + (p.z() < 2 * kR || p.z() > 1 - 2 * kR);
      // Up within 20 degrees along a wall, 30 in a corner (two walls lean it).
      EXPECT_GT(with_walls[i].y(), walls < 2 ? 0.94f : 0.86f) << p.transpose();
      waterline += walls == 1;
    }
  }
  EXPECT_GT(wall_layer, 500);
  EXPECT_GT(blind_surface, wall_layer / 2);
  EXPECT_GT(waterline, 20);
}

}  // namespace
}  // namespace spume
