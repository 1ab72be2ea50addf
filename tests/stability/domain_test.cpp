// Diffuse particles where they should not be: far outside the domain (removed at the first step,
// without overflow in the grid lookups), inside solids (pushed out, even from a sphere's exact
// centre), in the corners of a tank (they stay inside, on every wall at once), and thrown over an
// open tank's rim (they fall beside it to the ground before the domain deletes them).
#include <gtest/gtest.h>

#include "sim/scene/sim_scene.h"
#include "tests/stability/stability_support.h"

namespace spume {
namespace {

const double kDt = 1.0 / 50;

std::vector<FluidFrame> pool(const Vec3f& lo, const Vec3f& hi, int frames) {
  return stability::translating_block(lo, hi, 0.02f, Vec3f::Zero(), kDt, frames);
}

std::vector<Vec3f> far_away() {
  return {Vec3f(1e6f, 0, 0), Vec3f(-1e30f, 0.5f, 0.5f), Vec3f(0.5f, 3e38f, 0.5f), Vec3f(0.5f, 0.5f, -1e20f),
          Vec3f(-3e38f, -3e38f, -3e38f)};
}

TEST(StabilityDomain, ParticlesFarOutsideAreRemovedAtTheFirstStep) {
  for (DiffuseType type : {DiffuseType::Spray, DiffuseType::Foam, DiffuseType::Bubble}) {
    DiffuseSetup setup = stability::setup_with(0.02f, {{"k_ta", 0}, {"k_wc", 0}});
    setup.domain.min = Vec3f(-1, -1, -1), setup.domain.max = Vec3f(1, 1, 1);
    DiffuseSimulator sim(setup);
    sim.set_particles(stability::diffuse_at(far_away(), type, Vec3f(1, 2, 3)));
    const auto fluid = pool(Vec3f(0, 0, 0), Vec3f(0.2f, 0.2f, 0.2f), 3);
    FrameStats first{};
    const FrameStats s0 = sim.process_frame(fluid[0], &fluid[1], [&](const DiffuseFrame& f, const FrameStats&) {
      EXPECT_TRUE(stability::all_finite(f));
      for (DiffuseType t : f.types) EXPECT_EQ(t, DiffuseType::Spray);  // no fluid out there
    });
    (void)s0;
    first = sim.process_frame(fluid[1], &fluid[2], [](const DiffuseFrame& f, const FrameStats&) {
      EXPECT_TRUE(stability::all_finite(f));
    });
    EXPECT_EQ(first.removed, far_away().size()) << to_string(type);
    EXPECT_EQ(sim.particles().size(), 0u);
  }
}

TEST(StabilityDomain, WithoutADomainFarParticlesStayFinite) {
  DiffuseSetup setup = stability::setup_with(0.02f, {{"k_ta", 0}, {"k_wc", 0}});
  DiffuseSimulator sim(setup);
  sim.set_particles(stability::diffuse_at(far_away(), DiffuseType::Foam, Vec3f(1, 2, 3)));
  const auto run = stability::run_checked(sim, pool(Vec3f(0, 0, 0), Vec3f(0.2f, 0.2f, 0.2f), 5));
  EXPECT_EQ(run.removed, 0u);
  EXPECT_EQ(sim.particles().size(), far_away().size());
}

TEST(StabilityDomain, ParticlesInsideSolidsArePushedOut) {
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(0, 0, 0), tank.max = Vec3f(1, 1, 1);
  Solid box;
  box.kind = Solid::Kind::Box;
  box.min = Vec3f(0.4f, 0, 0.4f), box.max = Vec3f(0.6f, 0.2f, 0.6f);
  Solid ball;
  ball.kind = Solid::Kind::Sphere;
  ball.center = Vec3f(0.25f, 0.5f, 0.25f), ball.radius = 0.1f;
  DiffuseSetup setup = stability::setup_with(0.02f);
  setup.solids = SolidSet({tank, box, ball});
  setup.domain.min = Vec3f(-0.5f, -0.5f, -0.5f), setup.domain.max = Vec3f(1.5f, 2, 1.5f);
  // Inside the box, at the sphere's exact centre (no direction to leave by), under the floor,
  // beyond a side wall, and inside the box right at a tank corner.
  const std::vector<Vec3f> start = {Vec3f(0.5f, 0.1f, 0.5f), ball.center, Vec3f(0.5f, -0.3f, 0.5f),
                                    Vec3f(1.3f, 0.5f, 0.5f), Vec3f(0.45f, 0.01f, 0.45f)};
  for (DiffuseType type : {DiffuseType::Spray, DiffuseType::Foam, DiffuseType::Bubble}) {
    DiffuseSimulator sim(setup);
    sim.set_particles(stability::diffuse_at(start, type, Vec3f(0, -1, 0)));
    // A shallow pool on the floor around the box, moving a little so it emits too.
    auto fluid = stability::translating_block(Vec3f(0.02f, 0.02f, 0.02f), Vec3f(0.38f, 0.3f, 0.98f), 0.02f,
                                              Vec3f(0.5f, 0, 0), kDt, 6);
    const auto run = stability::run_checked(sim, fluid, true);
    for (const DiffuseFrame& f : run.frames)
      for (size_t i = 0; i < f.size(); ++i) {
        if (f.index == 0 && i < start.size()) continue;  // the input itself
        ASSERT_FALSE(setup.solids.inside(f.positions[i]))
            << to_string(type) << " frame " << f.index << " particle " << i << " at " << f.positions[i].transpose();
      }
    EXPECT_EQ(run.removed, 0u) << to_string(type);
  }
}

TEST(StabilityDomain, ParticlesInTheCornersOfATankStayInside) {
  for (bool open_top : {true, false}) {
    Solid tank;
    tank.kind = Solid::Kind::Tank;
    tank.min = Vec3f(0, 0, 0), tank.max = Vec3f(0.5f, 0.5f, 0.5f);
    tank.open_top = open_top;
    DiffuseSetup setup = stability::setup_with(0.02f);
    setup.solids = SolidSet({tank});
    setup.domain.min = Vec3f(-0.1f, -0.1f, -0.1f), setup.domain.max = Vec3f(0.6f, 1.5f, 0.6f);
    // Each of the 8 corners exactly, and just beyond it, thrown outwards through the corner.
    std::vector<Vec3f> start, velocity;
    for (int c = 0; c < 8; ++c) {
      const Vec3f corner((c & 1) ? 0.5f : 0.0f, (c & 2) ? 0.5f : 0.0f, (c & 4) ? 0.5f : 0.0f);
      const Vec3f out = (corner - Vec3f::Constant(0.25f)).normalized();
      start.push_back(corner), velocity.push_back(5.0f * out);
      start.push_back(corner + 1e-3f * out), velocity.push_back(5.0f * out);
    }
    for (DiffuseType type : {DiffuseType::Spray, DiffuseType::Foam, DiffuseType::Bubble}) {
      DiffuseSimulator sim(setup);
      DiffuseFrame d = stability::diffuse_at(start, type);
      d.velocities = velocity;
      sim.set_particles(d);
      // Fluid filling the bottom corners so classification sees fluid and walls together.
      const auto fluid = pool(Vec3f(0.02f, 0.02f, 0.02f), Vec3f(0.48f, 0.1f, 0.48f), 10);
      const auto run = stability::run_checked(sim, fluid, true);
      for (const DiffuseFrame& f : run.frames) {
        if (f.index == 0) continue;  // the input itself
        for (size_t i = 0; i < f.size(); ++i) {
          const Vec3f& p = f.positions[i];
          SCOPED_TRACE(str(to_string(type), open_top ? " open" : " closed", " frame ", f.index, " particle ", i,
                           " at ", p.transpose()));
          ASSERT_FALSE(sim.setup().solids.inside(p));
          ASSERT_GE(p.y(), 0.0f);
          if (!open_top) {
            ASSERT_LE(p.y(), 0.5f);
          }
          if (p.y() > 0.5f) continue;  // above an open tank's walls a particle may pass over them
          ASSERT_GE(p.x(), 0.0f);
          ASSERT_LE(p.x(), 0.5f);
          ASSERT_GE(p.z(), 0.0f);
          ASSERT_LE(p.z(), 0.5f);
        }
      }
      if (!open_top) {
        EXPECT_EQ(run.removed, 0u);
      }
    }
  }
}

// Spray thrown over the rim of an open tank [0, 1]^3 with walls 0.16 m thick (2 h at r = 0.02 m),
// ballistic (spray feels only gravity). The default domain reaches the tank's height (1 m) beyond
// each side wall, from its floor to 1 m above the rim:
// - A, from (0.9, 1.2) at 1.8 m/s along x, clears the wall's outer face x = 1.16 at t = 0.144 s, at
//   y = 1.2 - g t^2 / 2 = 1.098, and reaches the ground y = 0 at t = sqrt(2.4 / g) = 0.495 s, at
//   x = 1.79: landed, having fallen beside the tank;
// - B, from the same point at 6 m/s, reaches the domain's side x = 2 at t = 0.183 s, at y = 1.03:
//   removed in the air, not landed;
// - C, dropped inside the tank, rests on its floor and stays.
TEST(StabilityDomain, SprayOverAnOpenRimFallsBesideTheTankToTheGround) {
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(0, 0, 0), tank.max = Vec3f(1, 1, 1);
  tank.open_top = true;
  tank.wall_thickness = 0.16f;  // 2 h, as the diffuse stage sets it
  SimScene scene;
  scene.solids = SolidSet({tank});
  DiffuseSetup setup = stability::setup_with(0.02f, {{"k_ta", 0}, {"k_wc", 0}});
  setup.solids = scene.solids;
  setup.domain = default_domain(scene, Aabb());
  setup.ground = setup.solids.ground_below_tanks();
  EXPECT_EQ(setup.domain.min, Vec3f(-1, 0, -1));
  EXPECT_EQ(setup.domain.max, Vec3f(2, 2, 2));
  ASSERT_TRUE(setup.ground.has_value());
  EXPECT_EQ(setup.ground->up_axis, 1);
  EXPECT_EQ(setup.ground->level, 0.0f);

  DiffuseSimulator sim(setup);
  DiffuseFrame d = stability::diffuse_at({Vec3f(0.9f, 1.2f, 0.5f), Vec3f(0.9f, 1.2f, 0.5f), Vec3f(0.5f, 0.5f, 0.5f)},
                                         DiffuseType::Spray);
  d.velocities = {Vec3f(1.8f, 0, 0), Vec3f(6.0f, 0, 0), Vec3f::Zero()};
  sim.set_particles(d);
  // A little water in a far corner, so the frames have fluid; no emission.
  const auto fluid = pool(Vec3f(0.02f, 0.02f, 0.02f), Vec3f(0.1f, 0.06f, 0.1f), 30);  // 0.58 s
  const auto run = stability::run_checked(sim, fluid, true);
  EXPECT_EQ(run.removed, 2u);
  EXPECT_EQ(run.landed, 1u);
  ASSERT_EQ(sim.particles().size(), 1u);
  EXPECT_NEAR(sim.particles().positions[0].y(), 0.0f, 1e-3f);
  // A's last frame above the ground: beside the tank, beyond its wall, within a frame's fall (under
  // 0.1 m at 4.9 m/s) of the ground.
  float lowest_outside = 2.0f;
  for (const DiffuseFrame& f : run.frames)
    for (size_t i = 0; i < f.size(); ++i)
      if (f.positions[i].x() > 1.16f) lowest_outside = std::min(lowest_outside, f.positions[i].y());
  EXPECT_LT(lowest_outside, 0.1f);
  EXPECT_GT(lowest_outside, 0.0f);
}

// Two blocks thrown at each other along x and down onto the floor (r = 1 cm, 2 m/s each way, 3 m/s
// down): each newborn lies in a cylinder along its fluid particle's motion over the step, up to
// 0.02 s x 3.6 m/s = 7.2 cm long, so from the bottom layer (y = 1 cm) it reaches 5 cm into the floor,
// past half the wall's thickness (2h / 2 = 4 cm). There it once was pushed out through the wall's
// outer face and deleted with the domain (on the Mantaflow jet, 2319 of 580k newborns, and the domain
// warning in three frames). It belongs on its fluid particle's side: every newborn stays in the tank.
TEST(StabilityDomain, NewbornsSampledIntoTheFloorStayInTheTank) {
  const float r = 0.01f;
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(-0.5f, 0, -0.2f), tank.max = Vec3f(0.5f, 0.5f, 0.4f);
  tank.wall_thickness = 8.0f * r;  // 2 h, as the diffuse stage sets it
  SimScene scene;
  scene.solids = SolidSet({tank});
  DiffuseSetup setup = stability::setup_with(r, {{"k_ta", 20000}, {"k_wc", 20000}});
  setup.solids = scene.solids;
  setup.domain = default_domain(scene, Aabb());
  setup.ground = setup.solids.ground_below_tanks();
  const float side = 0.1f, gap = r;
  const auto a = testing::lattice(Vec3f(-side - gap, r, 0), Vec3f(-gap, side, side), 2 * r);
  const auto b = testing::lattice(Vec3f(gap, r, 0), Vec3f(side + gap, side, side), 2 * r);
  std::vector<Vec3f> x0 = a, v;
  x0.insert(x0.end(), b.begin(), b.end());
  for (size_t i = 0; i < x0.size(); ++i) v.push_back(Vec3f(i < a.size() ? 2.0f : -2.0f, -3.0f, 0));
  ASSERT_NEAR(std::min_element(x0.begin(), x0.end(), [](const Vec3f& p, const Vec3f& q) { return p.y() < q.y(); })->y(),
              r, 1e-6f);
  std::vector<FluidFrame> fluid;
  for (int k = 0; k < 2; ++k) {
    std::vector<Vec3f> x(x0.size());
    for (size_t i = 0; i < x.size(); ++i) x[i] = x0[i] + float(k * kDt) * v[i];
    fluid.push_back(testing::frame_of(k, k * kDt, x, v));
  }
  DiffuseSimulator sim(setup);
  const auto run = stability::run_checked(sim, fluid, true);
  ASSERT_GT(run.generated, 1000u);
  EXPECT_EQ(run.removed, 0u);
  size_t on_floor = 0;
  for (size_t i = 0; i < sim.particles().size(); ++i) {
    const Vec3f& p = sim.particles().positions[i];
    ASSERT_GE(p.y(), 0.0f) << i << " at " << p.transpose();
    on_floor += p.y() < 1e-3f;
  }
  EXPECT_GT(on_floor, 0u);  // some were sampled into the floor and stopped on it
}

TEST(StabilityDomain, AClosedTankIsItsOwnDomainAndGroundlessTanksHaveNone) {
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.min = Vec3f(1, 2, 3), tank.max = Vec3f(2, 4, 6);
  tank.open_top = false;
  SimScene scene;
  scene.solids = SolidSet({tank});
  const Aabb closed = default_domain(scene, Aabb());
  EXPECT_EQ(closed.min, tank.min);
  EXPECT_EQ(closed.max, tank.max);
  // Two tanks, the lower floor is the ground; tanks that disagree on up have none.
  Solid lower = tank;
  lower.min.y() = -1.0f;
  EXPECT_EQ(SolidSet({tank, lower}).ground_below_tanks()->level, -1.0f);
  Solid sideways = tank;
  sideways.up_axis = 2;
  EXPECT_FALSE(SolidSet({tank, sideways}).ground_below_tanks().has_value());
  EXPECT_FALSE(SolidSet().ground_below_tanks().has_value());
}

}  // namespace
}  // namespace spume
