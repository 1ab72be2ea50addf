// SolidSet::far_from, the broad phase of the per-particle solid tests: it may call a solid far only
// when no ball of that radius around the point meets it. Checked against distances computed here in
// double precision, on points placed just either side of the reach, far from the origin too, and with
// a rotation whose quaternion is as far off unit length as SolidSet::validate allows.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sim/geometry/solids.h"
#include "tests/support/solid_shapes.h"

namespace spume {
namespace {

using Vec3d = Eigen::Vector3d;

// Distance from p to the solid (0 inside), in double, with the rotation normalised.
double distance_to(const Solid& s, const Vec3d& p) {
  if (s.kind == Solid::Kind::Sphere) return std::max(0.0, (p - s.center.cast<double>()).norm() - double(s.radius));
  const Vec3d c = 0.5 * (s.min.cast<double>() + s.max.cast<double>()), half = 0.5 * (s.max - s.min).cast<double>();
  const Eigen::Quaterniond q = s.orientation.cast<double>().normalized();
  const Vec3d local = q.conjugate() * (p - c);
  return (local.cwiseAbs() - half).cwiseMax(0.0).norm();
}

// A point at `gap` from the solid's surface, outside it: on a face of a box (pushed along the face's
// normal) or along a ray of a sphere.
Vec3d point_beyond(const Solid& s, double gap, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  if (s.kind == Solid::Kind::Sphere) {
    Vec3d d(u(rng), u(rng), u(rng));
    d.normalize();
    return s.center.cast<double>() + (double(s.radius) + gap) * d;
  }
  const Vec3d c = 0.5 * (s.min.cast<double>() + s.max.cast<double>()), half = 0.5 * (s.max - s.min).cast<double>();
  const int axis = int(rng() % 3);
  const double side = rng() % 2 ? 1.0 : -1.0;
  Vec3d local(u(rng) * half.x(), u(rng) * half.y(), u(rng) * half.z());
  local[axis] = side * (half[axis] + gap);
  return c + s.orientation.cast<double>().normalized() * local;
}

Solid box_at(const Vec3f& centre, const Vec3f& half, const Quatf& orientation) {
  return testing::box_solid(centre - half, centre + half, orientation);
}

TEST(SolidBroadPhase, NeverCallsASolidFarThatABallOfTheReachMeets) {
  // A quaternion 5e-5 off unit length (validate allows 1e-4): rotating with it scales by up to 1e-4.
  Quatf tilted(Eigen::AngleAxisf(0.7f, Vec3f(1, 2, 3).normalized()));
  tilted.coeffs() *= 1.00005f;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> near_one(0.995, 1.005), spread(0.0, 1.0);
  int far_claims = 0, checked = 0;
  for (const Vec3f& origin : {Vec3f(0, 0, 0), Vec3f(1000, -500, 2000)}) {
    const SolidSet solids({box_at(origin + Vec3f(0.3f, 0.2f, 0.1f), Vec3f(0.12f, 0.4f, 0.05f), Quatf::Identity()),
                           box_at(origin + Vec3f(-1, 0.5f, 0), Vec3f(0.3f, 0.1f, 0.2f), tilted),
                           testing::sphere_solid(origin + Vec3f(2, 0, 0), 0.45f)});
    for (size_t i = 0; i < solids.solids().size(); ++i)
      for (float reach : {0.0f, 1e-3f, 0.03f}) {
        for (int k = 0; k < 20000; ++k) {
          // Half just short of the reach or just beyond it, half anywhere out to three times it; for reach
          // 0, just inside or outside the surface, or up to 1 cm out.
          const bool at_edge = k % 2 == 0;
          const double gap = reach > 0.0f ? reach * (at_edge ? near_one(rng) : 3.0 * spread(rng))
                                          : (at_edge ? 0.02 * (near_one(rng) - 1.0) : 0.01 * spread(rng));
          const Vec3d p = point_beyond(solids.solids()[i], gap, rng);
          const Vec3f pf = p.cast<float>();
          ++checked;
          if (!solids.far_from(i, pf, reach)) continue;
          ++far_claims;
          ASSERT_GT(distance_to(solids.solids()[i], pf.cast<double>()), double(reach))
              << "solid " << i << " called far from a point within " << reach << " m of it";
        }
      }
  }
  // And it does skip: a good share of the points beyond about twice the reach are called far.
  EXPECT_GT(far_claims, checked / 20);
}

TEST(SolidBroadPhase, SkipsWhatIsWellClearAndNeverATank) {
  const Solid cube = box_at(Vec3f(0, 0, 0), Vec3f(0.5f, 0.5f, 0.5f), Quatf::Identity());
  const SolidSet solids({cube, testing::sphere_solid(Vec3f(3, 0, 0), 0.5f),
                         testing::tank_solid(Vec3f(-5, -5, -5), Vec3f(5, 5, 5))});
  const float h = 0.03f;
  // 1.1 h beyond a face (the bounds are widened by 1e-3 of the box's half diagonal and 1e-3 of h).
  EXPECT_TRUE(solids.far_from(0, Vec3f(0.5f + 1.1f * h, 0, 0), h));
  EXPECT_FALSE(solids.far_from(0, Vec3f(0.5f + 0.9f * h, 0, 0), h));
  EXPECT_TRUE(solids.far_from(1, Vec3f(3, 0.5f + 1.1f * h, 0), h));
  EXPECT_FALSE(solids.far_from(1, Vec3f(3, 0.5f + 0.9f * h, 0), h));
  // A sphere's bounding box is loose at its corners: there it is not called far, only not skipped.
  EXPECT_FALSE(solids.far_from(1, Vec3f(3.4f, 0.4f, 0.4f), h));
  // A tank holds its free space inside: never skipped, wherever the point.
  for (const Vec3f& p : {Vec3f(0, 0, 0), Vec3f(100, 0, 0), Vec3f(-4.99f, 0, 0)}) EXPECT_FALSE(solids.far_from(2, p, h));
  // Poses move the bounds with the body.
  Solid body = cube;
  body.dynamics.enabled = true, body.dynamics.density = 500.0f;
  const SolidSet bodies({body});
  BodyPose pose;
  pose.solid = 0, pose.position = Vec3f(10, 0, 0);
  const SolidSet moved = bodies.posed({pose});
  EXPECT_TRUE(moved.far_from(0, Vec3f(0, 0, 0), h));
  EXPECT_FALSE(moved.far_from(0, Vec3f(10, 0, 0), h));
}

}  // namespace
}  // namespace spume
