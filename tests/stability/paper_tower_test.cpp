// The paper's tower (scenes/tower_paper.json: 1000 cubes of 4 cm, 700 kg/m^3, friction 0.6, stacked
// 10 x 10 x 10 on the tank floor) under gravity alone, as the fluid solver steps it: Bullet started
// afresh from the cubes' poses at every frame (FluidSolver::advance_to), in steps of the scene's
// 1.09 ms cap. A stack that jittered or crept when its contacts were rebuilt every frame would move;
// standing, no cube moves 1 mm in half a second (Bullet settles a stack into its contacts by a
// fraction of its collision margin, r/2 = 1.3 mm).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sim/fluid/rigid_bodies.h"

namespace spume::fluid {
namespace {

TEST(StabilityPaperTower, StandsUnderGravityWithBulletStartedAfreshEveryFrame) {
  std::vector<Solid> solids(1);
  solids[0].kind = Solid::Kind::Tank;
  solids[0].min = Vec3f(0, 0, 0), solids[0].max = Vec3f(2.0f, 1.2f, 1.0f);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i)
      for (int k = 0; k < 10; ++k) {
        Solid cube;
        cube.kind = Solid::Kind::Box;
        cube.min = Vec3f(1.3f + 0.04f * i, 0.04f * j, 0.3f + 0.04f * k);
        cube.max = cube.min + Vec3f::Constant(0.04f);
        cube.dynamics.enabled = true, cube.dynamics.density = 700.0f, cube.dynamics.friction = 0.6f;
        solids.push_back(cube);
      }
  const float r = 0.0026f;  // the scene's particle radius: Bullet's margin r/2, the skin 2r
  RigidBodies bodies(SolidSet(solids), Vec3f(0, -9.81f, 0), 0.5f * r, 2.0f * r);
  ASSERT_EQ(bodies.size(), 1000u);
  const std::vector<BodyPose> start = bodies.poses();
  const std::vector<Vec3d> none(bodies.size(), Vec3d::Zero());
  const double fps = 30.0, cap = 1.0914e-3;
  double t = 0.0;
  for (int frame = 1; frame <= 15; ++frame) {  // half a second
    bodies.reset(bodies.poses(), t);
    const double end = frame / fps;
    const int steps = int(std::ceil((end - t) / cap - 1e-9));
    const double dt = (end - t) / steps;
    for (int s = 0; s < steps; ++s, t += dt) bodies.step(t, dt, none, none);
    t = end;
  }
  double moved = 0.0, fastest = 0.0;
  for (size_t b = 0; b < bodies.size(); ++b) {
    moved = std::max(moved, double((bodies.poses()[b].position - start[b].position).norm()));
    fastest = std::max(fastest, double(bodies.poses()[b].velocity.norm()));
  }
  EXPECT_LT(moved, 1e-3) << "m: the tower settled or crept";
  EXPECT_LT(fastest, 0.01) << "m/s";
  std::printf("tower under gravity, 0.5 s: the most any cube moved %.3g mm, fastest %.3g m/s\n", 1e3 * moved, fastest);
}

}  // namespace
}  // namespace spume::fluid
