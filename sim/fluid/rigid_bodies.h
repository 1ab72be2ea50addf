#pragma once
// The dynamic solids of a scene as rigid bodies, simulated by Bullet (btDiscreteDynamicsWorld, box
// and sphere shapes): gravity, the forces and torques the fluid exerts (fluid/coupling.h), and
// contacts with each other, the tank walls, static solids and kinematic solids (Bullet kinematic
// bodies following their motion; these three grown by a skin, see the constructor). Contacts have restitution 0 and Coulomb friction (a body's
// `friction`; static and kinematic solids have 1, and Bullet multiplies the two coefficients).
//
// Bullet is only seen by rigid_bodies.cpp. It runs single-threaded and is deterministic for identical
// inputs, so bodies move identically for any thread count of the fluid solver as long as the
// forces are summed in a fixed order (coupling.h does).
#include <memory>
#include <vector>

#include "sim/core/vec.h"
#include "sim/geometry/solids.h"

namespace spume::fluid {

class RigidBodies {
 public:
  RigidBodies();  // no bodies
  // One body per dynamic solid of `solids`, in solid order, at its initial pose and at rest.
  // `margin` (m): Bullet's collision margin for boxes (kept inside the box, so the contact surface
  // stays the box's); use a fraction of the particle radius. `skin` (m): how far the bodies are kept
  // from the tanks' walls and the static and kinematic solids (each grown by it for Bullet): the
  // film of water a body lands on cannot drain thinner than a particle, and a body let closer
  // crushes it (MODEL.md §10). Bodies touch each other. Throws Error for invalid solids.
  RigidBodies(const SolidSet& solids, const Vec3f& gravity, float margin, float skin = 0.0f);
  ~RigidBodies();
  RigidBodies(RigidBodies&&) noexcept;
  RigidBodies& operator=(RigidBodies&&) noexcept;

  bool empty() const { return poses_.empty(); }
  size_t size() const { return poses_.size(); }
  // Current pose of each body, in solid order (BodyPose::solid says which).
  const std::vector<BodyPose>& poses() const { return poses_; }
  // Body index of solid s, or -1 when s is not dynamic.
  int body_of_solid(size_t s) const { return s < body_of_solid_.size() ? body_of_solid_[s] : -1; }
  float mass(size_t body) const { return masses_[body]; }

  // Advances the bodies from t to t + dt under gravity plus, per body, `force` (N, at the centre of
  // mass) and `torque` (N m, about it), held constant over the step, which Bullet takes in substeps
  // of at most kMaxSubstep. Kinematic solids move to their offset at each substep's end.
  void step(double t, double dt, const std::vector<Vec3d>& force, const std::vector<Vec3d>& torque);

  // Puts every body at `poses` (as poses() gave them) at time t, with Bullet's contact caches and
  // warm-started impulses emptied and its broadphase rebuilt in the order the bodies were made: what
  // follows depends on the poses alone, so the same poses give the same steps in any RigidBodies of
  // the same solids (a fresh one restoring a saved state, or one that has run for a while).
  void reset(const std::vector<BodyPose>& poses, double t);

  static constexpr double kMaxSubstep = 1.0 / 1000.0;  // s

 private:
  struct World;
  std::unique_ptr<World> world_;
  std::vector<BodyPose> poses_;
  std::vector<int> body_of_solid_;
  std::vector<float> masses_;
};

}  // namespace spume::fluid
