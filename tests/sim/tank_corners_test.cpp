// Steps across a tank's edges and into its corners stop at every wall they meet,
// steps over an open rim still go over, and push-out leaves a solid by a skin float can represent
// however far from the origin the scene sits (bug 4). Expectations are worked by hand: a step that
// ends beyond a set of walls and stops at each of them keeps its motion along them, so it ends with
// every crossed coordinate on its wall plus the skin and every other coordinate where it was going.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "sim/diffuse/simulator.h"
#include "tests/support/test_fluids.h"

namespace spume {
namespace {

constexpr float kSkin = 1e-4f;

Solid tank_solid(const Vec3f& lo, const Vec3f& hi, bool open_top, float wall_thickness) {
  Solid s;
  s.kind = Solid::Kind::Tank;
  s.min = lo, s.max = hi, s.open_top = open_top, s.wall_thickness = wall_thickness;
  return s;
}

// [0,1]^3 with walls 0.16 m thick (2 h at r = 0.02 m): a 0.3 m overshoot is past the wall's middle,
// where push_out alone would push the particle out through the wall's outer face.
SolidSet unit_tank(bool open_top) { return SolidSet({tank_solid(Vec3f::Zero(), Vec3f::Ones(), open_top, 0.16f)}); }

// What a step to `to` inside a closed [0,1]^3 must end as: each coordinate beyond a wall on that
// wall plus the skin, the others where the step was going; the velocity into each crossed wall gone.
void expect_clipped(const Vec3f& to, const Vec3f& v_before, const Vec3f& p, const Vec3f& v, const std::string& what) {
  for (int a = 0; a < 3; ++a) {
    if (to[a] < 0.0f) {
      EXPECT_FLOAT_EQ(p[a], kSkin) << what << " axis " << a;
      EXPECT_EQ(v[a], 0.0f) << what << " axis " << a;
    } else if (to[a] > 1.0f) {
      EXPECT_FLOAT_EQ(p[a], 1.0f - kSkin) << what << " axis " << a;
      EXPECT_EQ(v[a], 0.0f) << what << " axis " << a;
    } else {
      EXPECT_EQ(p[a], to[a]) << what << " axis " << a;
      EXPECT_EQ(v[a], v_before[a]) << what << " axis " << a;
    }
  }
}

TEST(TankWallStops, AStepThroughTheFloorAndASideWallStopsAtBoth) {
  // (0.9, 0.05) -> (1.3, -0.3): the floor is met first (at x = 0.957), the x = 1 wall's plane is
  // crossed below the floor. Before: the floor stopped it, x stayed 1.3, and push_out sent it out
  // through the wall's outer face.
  const SolidSet solids = unit_tank(true);
  Vec3f p(1.3f, -0.3f, 0.5f), v(20.0f, -17.5f, 1.0f);
  EXPECT_TRUE(solids.stop_at_tank_walls(Vec3f(0.9f, 0.05f, 0.5f), p, v, kSkin));
  EXPECT_FLOAT_EQ(p.x(), 1.0f - kSkin);
  EXPECT_FLOAT_EQ(p.y(), kSkin);
  EXPECT_EQ(p.z(), 0.5f);
  EXPECT_EQ(v, Vec3f(0.0f, 0.0f, 1.0f));
  solids.push_out(p, v, kSkin);
  EXPECT_FALSE(solids.inside(p));
  EXPECT_FLOAT_EQ(p.x(), 1.0f - kSkin);
}

TEST(TankWallStops, EveryCornerInEveryCrossingOrderStopsAtAllThreeWalls) {
  // A closed tank: every corner is three walls. From 0.1 inside a corner to 0.05, 0.2 and 0.4 beyond
  // its three walls in each of the 6 orders: the walls are met in different orders, every one stops it.
  const SolidSet solids = unit_tank(false);
  const std::array<float, 3> overshoot = {0.05f, 0.2f, 0.4f};
  std::array<int, 3> order = {0, 1, 2};
  int cases = 0;
  for (int corner = 0; corner < 8; ++corner) {
    do {
      Vec3f from, to;
      for (int a = 0; a < 3; ++a) {
        const bool high = (corner >> a) & 1;
        const float o = overshoot[size_t(order[size_t(a)])];
        from[a] = high ? 0.9f - 0.01f * float(a) : 0.1f + 0.01f * float(a);
        to[a] = high ? 1.0f + o : -o;
      }
      Vec3f p = to, v = (to - from) / 0.02f;
      const Vec3f v_before = v;
      const std::string what = "corner " + std::to_string(corner) + " order " + std::to_string(order[0]) +
                               std::to_string(order[1]) + std::to_string(order[2]);
      EXPECT_TRUE(solids.stop_at_tank_walls(from, p, v, kSkin)) << what;
      expect_clipped(to, v_before, p, v, what);
      solids.push_out(p, v, kSkin);
      EXPECT_FALSE(solids.inside(p)) << what;
      ++cases;
    } while (std::next_permutation(order.begin(), order.end()));
  }
  EXPECT_EQ(cases, 48);
}

TEST(TankWallStops, EveryEdgeInBothCrossingOrdersStopsAtBothWalls) {
  // The 12 edges of a closed tank, each crossed both ways round (0.05 beyond one wall and 0.35
  // beyond the other, then swapped), the third coordinate moving along the edge.
  const SolidSet solids = unit_tank(false);
  int cases = 0;
  for (int along = 0; along < 3; ++along)
    for (int side = 0; side < 4; ++side)
      for (bool swap : {false, true}) {
        const int a = (along + 1) % 3, b = (along + 2) % 3;
        const bool high_a = side & 1, high_b = side & 2;
        Vec3f from, to;
        from[along] = 0.5f, to[along] = 0.6f;
        from[a] = high_a ? 0.92f : 0.08f;
        from[b] = high_b ? 0.9f : 0.1f;
        const float oa = swap ? 0.35f : 0.05f, ob = swap ? 0.05f : 0.35f;
        to[a] = high_a ? 1.0f + oa : -oa;
        to[b] = high_b ? 1.0f + ob : -ob;
        Vec3f p = to, v = (to - from) / 0.02f;
        const Vec3f v_before = v;
        const std::string what = "edge along " + std::to_string(along) + " side " + std::to_string(side) +
                                 (swap ? " swapped" : "");
        EXPECT_TRUE(solids.stop_at_tank_walls(from, p, v, kSkin)) << what;
        expect_clipped(to, v_before, p, v, what);
        solids.push_out(p, v, kSkin);
        EXPECT_FALSE(solids.inside(p)) << what;
        ++cases;
      }
  EXPECT_EQ(cases, 24);
}

TEST(TankWallStops, StepsOverTheOpenRimStillGoOver) {
  const SolidSet solids = unit_tank(true);
  // Over a side wall: the x = 1 plane is crossed at y = 0.95 + 0.35 / 4 = 1.04, above the rim.
  Vec3f p(1.3f, 1.3f, 0.5f), v(20, 17.5f, 0);
  EXPECT_FALSE(solids.stop_at_tank_walls(Vec3f(0.9f, 0.95f, 0.5f), p, v, kSkin));
  EXPECT_EQ(p, Vec3f(1.3f, 1.3f, 0.5f));
  // Over a corner of the rim: both side planes are crossed at t = 0.2, y = 0.98 + 0.044 = 1.024.
  p = Vec3f(1.2f, 1.2f, 1.2f), v = Vec3f(1, 1, 1);
  EXPECT_FALSE(solids.stop_at_tank_walls(Vec3f(0.95f, 0.98f, 0.95f), p, v, kSkin));
  EXPECT_EQ(p, Vec3f(1.2f, 1.2f, 1.2f));
  // ... and on the low side: the x = 0 and z = 0 planes at t = 0.25, y = 0.96 + 0.06 = 1.02.
  p = Vec3f(-0.15f, 1.2f, -0.3f);
  EXPECT_FALSE(solids.stop_at_tank_walls(Vec3f(0.05f, 0.96f, 0.1f), p, v, kSkin));
  EXPECT_EQ(p, Vec3f(-0.15f, 1.2f, -0.3f));
  // Below the rim on one wall, over it on the other: (0.9, 0.85, 0.8) -> (1.3, 1.3, 1.1) crosses
  // x = 1 first, at t = 0.25, y = 0.9625, z = 0.875 (stop, slide up the wall); the slide from there
  // to (1, 1.3, 1.1) crosses z = 1 5/9 of the way along, at y = 1.15, above the rim: over.
  p = Vec3f(1.3f, 1.3f, 1.1f), v = Vec3f(20, 10, 25);
  EXPECT_TRUE(solids.stop_at_tank_walls(Vec3f(0.9f, 0.85f, 0.8f), p, v, kSkin));
  EXPECT_FLOAT_EQ(p.x(), 1.0f - kSkin);
  EXPECT_EQ(p.y(), 1.3f);
  EXPECT_EQ(p.z(), 1.1f);
  EXPECT_EQ(v, Vec3f(0, 10, 25));
  // Into the floor and a side wall from above the rim (falling in): stops at both.
  p = Vec3f(1.1f, -0.2f, 0.5f), v = Vec3f(5, -60, 0);
  EXPECT_TRUE(solids.stop_at_tank_walls(Vec3f(0.9f, 1.1f, 0.5f), p, v, kSkin));
  EXPECT_FLOAT_EQ(p.x(), 1.0f - kSkin);
  EXPECT_FLOAT_EQ(p.y(), kSkin);
}

TEST(TankWallStops, FastSprayIntoACornerIsNotLost) {
  // 20 m/s towards the z = 0 wall and 15 m/s towards x = 0 from 0.2 m off both: the z wall is met
  // first (half way through the 0.02 s step), the x = 0 plane only beyond the z wall, and the step
  // ends 0.1 m into the x wall (past the middle of its 0.16 m). Before, the z wall stopped it, the
  // x wall was never tested again, push_out sent it out through the x wall's outer face and the
  // domain deleted it.
  DiffuseSetup s;
  s.fluid.particle_radius = 0.02f;
  s.fluid.support_radius = 0.08f;
  s.fluid.fps = 50.0;
  s.params.k_ta = s.params.k_wc = 0.0f;
  s.solids = unit_tank(true);
  s.domain = Aabb{Vec3f::Zero(), Vec3f(1.0f, 2.0f, 1.0f)};
  DiffuseSimulator sim(s);
  DiffuseFrame d;
  d.resize(1);
  d.ids[0] = diffuse_id(0, 5, 0);
  d.positions[0] = Vec3f(0.2f, 0.8f, 0.2f);
  d.velocities[0] = Vec3f(-15.0f, 0.0f, -20.0f);
  d.lifetimes[0] = 2.0f;
  d.types[0] = DiffuseType::Spray;
  sim.set_particles(d);
  const auto water = testing::lattice(Vec3f(0.5f, 0.02f, 0.5f), Vec3f(0.7f, 0.1f, 0.7f), 0.04f);
  std::vector<FluidFrame> seq;
  for (int k = 0; k < 4; ++k) seq.push_back(testing::frame_of(k, k / 50.0, water, std::vector<Vec3f>(water.size(), Vec3f::Zero())));
  uint64_t removed = 0;
  for (int k = 0; k + 1 < 4; ++k)
    removed += sim.process_frame(seq[size_t(k)], &seq[size_t(k) + 1], [](const DiffuseFrame&, const FrameStats&) {}).removed;
  EXPECT_EQ(removed, 0u);
  ASSERT_EQ(sim.particles().size(), 1u) << "lost through the wall";
  const Vec3f x = sim.particles().positions[0];
  EXPECT_NEAR(x.x(), 0.0f, 1e-3f);
  EXPECT_NEAR(x.z(), 0.0f, 1e-3f);
  EXPECT_NEAR(x.y(), 0.8f - 0.5f * 9.81f * 0.06f * 0.06f, 1e-3f);  // falling down the corner
}

// --- Far from the origin (bug 4) ---------------------------------------------------------------

// 10 km out, float positions are 1/1024 m apart: a skin of 1e-4 r = 2 um is far below half of that.
const Vec3f kFar(10000.0f, 10000.0f, 10000.0f);
constexpr float kR = 0.02f;
constexpr float kRSkin = 1e-4f * kR;

TEST(FarFromOrigin, PushOutLeavesATankWallByARepresentableSkin) {
  const SolidSet solids({tank_solid(kFar, kFar + Vec3f(1, 1, 1), true, 0.16f)});
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> depth(0.0f, 0.07f), across(0.1f, 0.9f);
  for (int k = 0; k < 200; ++k) {
    // Under the floor, and beyond the x = max wall.
    Vec3f p = kFar + Vec3f(across(rng), -depth(rng), across(rng)), v(0, -1, 0);
    if (!solids.inside(p)) continue;
    EXPECT_TRUE(solids.push_out(p, v, kRSkin));
    EXPECT_FALSE(solids.inside(p));
    // Above the floor by at least the skin asked for (in double: the float spacing here is 1 mm).
    EXPECT_GE(double(p.y()) - double(kFar.y()), double(kRSkin)) << k;
    Vec3f q = kFar + Vec3f(1.0f + depth(rng), across(rng), across(rng)), w(1, 0, 0);
    if (!solids.inside(q)) continue;
    EXPECT_TRUE(solids.push_out(q, w, kRSkin));
    EXPECT_GE(double(kFar.x()) + 1.0 - double(q.x()), double(kRSkin)) << k;
  }
  // A step through the floor stops above it, not on it.
  Vec3f p = kFar + Vec3f(0.5f, -0.3f, 0.5f), v(0, -10, 0);
  EXPECT_TRUE(solids.stop_at_tank_walls(kFar + Vec3f(0.5f, 0.1f, 0.5f), p, v, kRSkin));
  EXPECT_GT(double(p.y()) - double(kFar.y()), double(kRSkin));
  EXPECT_FALSE(solids.inside(p));
}

TEST(FarFromOrigin, PushOutLeavesBoxesAndSpheresWhoseCentresRound) {
  // A box whose corners are an odd number of float spacings apart (its centre is not a float) and a
  // sphere, 10 km out: 2000 points inside each are pushed out, and each ends outside.
  const float ulp = std::nextafter(10000.0f, 2e4f) - 10000.0f;
  Solid box;
  box.kind = Solid::Kind::Box;
  box.min = kFar + Vec3f(ulp, 3 * ulp, 5 * ulp);
  box.max = kFar + Vec3f(0.5f, 0.3f + ulp, 0.4f);
  Solid turned = box.translated(Vec3f(2, 0, 0));
  turned.orientation = Quatf(Eigen::AngleAxisf(0.3f, Vec3f(0, 1, 0)));
  Solid ball;
  ball.kind = Solid::Kind::Sphere;
  ball.center = kFar + Vec3f(5.0f, 0.1f + ulp, 0.2f), ball.radius = 0.2f + 3 * ulp;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  for (const Solid& s : {box, turned, ball}) {
    const SolidSet solids({s});
    int pushed = 0;
    for (int k = 0; k < 2000; ++k) {
      const Vec3f c = s.centre();
      const Vec3f extent = s.kind == Solid::Kind::Sphere ? Vec3f::Constant(2 * s.radius) : Vec3f(s.max - s.min);
      Vec3f p = c + Vec3f(u(rng) * extent.x(), u(rng) * extent.y(), u(rng) * extent.z()), v(1, 1, 1);
      if (!solids.inside(p)) continue;
      ++pushed;
      solids.push_out(p, v, kRSkin);
      ASSERT_FALSE(solids.inside(p)) << int(s.kind) << " point " << k;
    }
    EXPECT_GT(pushed, 400);
  }
}

TEST(FarFromOrigin, SprayInATank10KmOutStaysAboveTheFloorAndInside) {
  // A spray particle falls onto the floor of a tank 10 km from the origin and rests there: every
  // frame it is inside the tank, above the floor (by the skin), never in the floor.
  DiffuseSetup s;
  s.fluid.particle_radius = kR;
  s.fluid.support_radius = 4 * kR;
  s.fluid.fps = 50.0;
  s.params.k_ta = s.params.k_wc = 0.0f;
  const SolidSet solids({tank_solid(kFar, kFar + Vec3f(1, 1, 1), true, 0.16f)});
  s.solids = solids;
  DiffuseSimulator sim(s);
  DiffuseFrame d;
  d.resize(1);
  d.ids[0] = diffuse_id(0, 5, 0);
  d.positions[0] = kFar + Vec3f(0.3f, 0.05f, 0.5f);
  d.velocities[0] = Vec3f(0.0f, -3.0f, 0.0f);
  d.lifetimes[0] = 2.0f;
  d.types[0] = DiffuseType::Spray;
  sim.set_particles(d);
  const auto water = testing::lattice(kFar + Vec3f(0.7f, 0.02f, 0.4f), kFar + Vec3f(0.8f, 0.1f, 0.5f), 2 * kR);
  std::vector<FluidFrame> seq;
  for (int k = 0; k < 8; ++k) seq.push_back(testing::frame_of(k, k / 50.0, water, std::vector<Vec3f>(water.size(), Vec3f::Zero())));
  int frames = 0;
  for (int k = 0; k < 8; ++k)
    sim.process_frame(seq[size_t(k)], k + 1 < 8 ? &seq[size_t(k) + 1] : nullptr, [&](const DiffuseFrame& f, const FrameStats&) {
      ASSERT_EQ(f.size(), 1u) << k;
      const Vec3f x = f.positions[0];
      EXPECT_FALSE(solids.inside(x)) << k;
      EXPECT_GT(double(x.y()), double(kFar.y())) << k;
      ++frames;
    });
  EXPECT_EQ(frames, 8);
  // Resting on the floor, within a few float spacings (1 mm each).
  EXPECT_LT(double(sim.particles().positions[0].y()) - double(kFar.y()), 0.005);
}

}  // namespace
}  // namespace spume
