#include "sim/fluid/rigid_bodies.h"

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>

#include "sim/core/error.h"

namespace spume::fluid {
namespace {

btVector3 bt(const Vec3f& v) { return btVector3(v.x(), v.y(), v.z()); }
btVector3 bt(const Vec3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Vec3f vec(const btVector3& v) { return Vec3f(float(v.x()), float(v.y()), float(v.z())); }

btTransform pose_transform(const Vec3f& centre, const Quatf& q) {
  return btTransform(btQuaternion(q.x(), q.y(), q.z(), q.w()), bt(centre));
}

// Collision groups. The bodies meet each other and one copy of every static and kinematic solid:
// the copy grown by the skin, or, for a body that starts within the skin of one (a tower standing on
// the floor), the solid as it is, which it rests on as placed.
constexpr int kBodyGroup = 64, kSkinnedGroup = 128, kPlainGroup = 256;
constexpr int kMaskOfABody = -1;  // World::add: decided by World::body_mask once the solids are in

// Whether any contact the test finds goes deeper than touching.
struct OverlapCount : btCollisionWorld::ContactResultCallback {
  int overlaps = 0;
  btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int, const btCollisionObjectWrapper*,
                           int, int) override {
    overlaps += cp.getDistance() < 0;
    return 0;
  }
};

}  // namespace

struct RigidBodies::World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> objects;  // every Bullet body, static ones included
  std::vector<std::pair<int, int>> filters;           // per object: its collision group and mask
  std::vector<btRigidBody*> bodies;                   // the dynamic ones, in body order
  struct Kinematic {
    btRigidBody* object;  // each copy (skinned, plain) is listed
    const Solid* solid;   // points into `solids`
  };
  std::vector<Kinematic> kinematic;
  std::vector<Solid> solids;  // the scene's solids at their initial pose

  ~World() {
    for (auto& o : objects) world.removeRigidBody(o.get());
  }

  // `grow`: m added to the solid on every side.
  btCollisionShape* shape_of(const Solid& s, float margin, float grow) {
    if (s.kind == Solid::Kind::Sphere) {
      shapes.push_back(std::make_unique<btSphereShape>(s.radius + grow));
    } else {
      const Vec3f half = 0.5f * (s.max - s.min) + Vec3f::Constant(grow);
      auto box = std::make_unique<btBoxShape>(bt(half));
      box->setMargin(std::min(margin, 0.25f * half.minCoeff()));  // btBoxShape keeps its outer size
      shapes.push_back(std::move(box));
    }
    return shapes.back().get();
  }

  btRigidBody* add(btCollisionShape* shape, const btTransform& where, double mass, float friction, int group, int mask) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0.0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform = where;
    info.m_friction = friction;
    info.m_restitution = 0.0;
    info.m_linearDamping = 0.0;
    info.m_angularDamping = 0.0;
    objects.push_back(std::make_unique<btRigidBody>(info));
    btRigidBody* o = objects.back().get();
    if (mask < 0) mask = body_mask(o);
    filters.emplace_back(group, mask);
    world.addRigidBody(o, group, mask);
    return o;
  }

  // Whom a body meets: the other bodies and the grown solids, or the solids as they are when it starts
  // within their skin (pushed out of the skin, a body placed on the floor would leap off it).
  int body_mask(btRigidBody* body) {
    OverlapCount test;
    test.m_collisionFilterGroup = kBodyGroup;
    test.m_collisionFilterMask = kSkinnedGroup;
    world.contactTest(body, test);
    return kBodyGroup | (test.overlaps ? kPlainGroup : kSkinnedGroup);
  }

  // A static or kinematic solid, twice: grown by `skin`, and as it is (once without a skin).
  std::vector<btRigidBody*> add_static(const Solid& s, const btTransform& where, float margin, float skin) {
    if (!(skin > 0.0f)) return {add(shape_of(s, margin, 0.0f), where, 0.0, 1.0f, kSkinnedGroup | kPlainGroup, kBodyGroup)};
    return {add(shape_of(s, margin, skin), where, 0.0, 1.0f, kSkinnedGroup, kBodyGroup),
            add(shape_of(s, margin, 0.0f), where, 0.0, 1.0f, kPlainGroup, kBodyGroup)};
  }

  // Five or six slabs as thick as the tank is large, outside its walls and overlapping at the edges,
  // each reaching `skin` into the tank.
  void add_tank(const Solid& s, float margin, float skin) {
    const Vec3f extent = s.max - s.min;
    const float thick = extent.maxCoeff();
    for (int a = 0; a < 3; ++a)
      for (int side = 0; side < 2; ++side) {
        if (side == 1 && s.open_top && a == s.up_axis) continue;
        Vec3f half = 0.5f * extent + Vec3f::Constant(thick);
        half[a] = 0.5f * thick;
        Vec3f centre = 0.5f * (s.min + s.max);
        centre[a] = side == 0 ? s.min[a] - 0.5f * thick : s.max[a] + 0.5f * thick;
        Solid slab;
        slab.kind = Solid::Kind::Box;
        slab.min = centre - half;
        slab.max = centre + half;
        add_static(slab, pose_transform(centre, Quatf::Identity()), margin, skin);
      }
  }
};

RigidBodies::RigidBodies() = default;
RigidBodies::~RigidBodies() = default;
RigidBodies::RigidBodies(RigidBodies&&) noexcept = default;
RigidBodies& RigidBodies::operator=(RigidBodies&&) noexcept = default;

RigidBodies::RigidBodies(const SolidSet& solids, const Vec3f& gravity, float margin, float skin) {
  solids.validate();
  body_of_solid_.assign(solids.solids().size(), -1);
  if (!solids.any_dynamic()) return;
  world_ = std::make_unique<World>();
  World& w = *world_;
  w.solids = solids.solids();
  w.world.setGravity(bt(gravity));
  // The static and kinematic solids first: each body tests whether it starts within their skin.
  for (const Solid& s : w.solids) {
    if (s.kind == Solid::Kind::Tank) {
      w.add_tank(s, margin, skin);
    } else if (!s.dynamics.enabled) {
      for (btRigidBody* o : w.add_static(s, pose_transform(s.centre(), s.orientation), margin, skin))
        if (s.motion.moving()) {
          o->setCollisionFlags(o->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
          o->setActivationState(DISABLE_DEACTIVATION);
          o->setWorldTransform(pose_transform(s.centre() + s.motion.offset(0.0), s.orientation));
          o->setInterpolationWorldTransform(o->getWorldTransform());
          w.kinematic.push_back({o, &s});
        }
    }
  }
  for (size_t i = 0; i < w.solids.size(); ++i) {
    const Solid& s = w.solids[i];
    const btTransform where = pose_transform(s.centre(), s.orientation);
    if (s.dynamics.enabled) {
      const double mass = s.dynamics.mass > 0.0f ? double(s.dynamics.mass) : double(s.dynamics.density) * s.volume();
      btRigidBody* body =
          w.add(w.shape_of(s, margin, 0.0f), where, mass, s.dynamics.friction, kBodyGroup, kMaskOfABody);
      body->setActivationState(DISABLE_DEACTIVATION);  // the fluid may push a body at rest at any time
      body_of_solid_[i] = int(w.bodies.size());
      w.bodies.push_back(body);
      masses_.push_back(float(mass));
      BodyPose pose;
      pose.solid = uint32_t(i);
      pose.position = s.centre();
      pose.orientation = s.orientation;
      poses_.push_back(pose);
    }
  }
}

void RigidBodies::step(double t, double dt, const std::vector<Vec3d>& force, const std::vector<Vec3d>& torque) {
  if (empty() || !(dt > 0.0)) return;
  World& w = *world_;
  const int substeps = std::max(1, int(std::ceil(dt / kMaxSubstep - 1e-9)));
  const double h = dt / substeps;
  for (int k = 1; k <= substeps; ++k) {
    const double t_end = k == substeps ? t + dt : t + k * h;
    for (const World::Kinematic& m : w.kinematic)
      m.object->setWorldTransform(pose_transform(m.solid->centre() + m.solid->motion.offset(t_end), m.solid->orientation));
    for (size_t b = 0; b < w.bodies.size(); ++b) {
      w.bodies[b]->applyCentralForce(bt(force[b]));
      w.bodies[b]->applyTorque(bt(torque[b]));
    }
    w.world.stepSimulation(btScalar(h), 0);  // 0: exactly one step of h (forces are cleared after it)
  }
  for (size_t b = 0; b < w.bodies.size(); ++b) {
    const btRigidBody& body = *w.bodies[b];
    const btTransform& x = body.getWorldTransform();
    const btQuaternion q = x.getRotation();
    BodyPose& pose = poses_[b];
    pose.position = vec(x.getOrigin());
    pose.orientation = Quatf(float(q.w()), float(q.x()), float(q.y()), float(q.z())).normalized();
    pose.velocity = vec(body.getLinearVelocity());
    pose.angular_velocity = vec(body.getAngularVelocity());
  }
}

void RigidBodies::reset(const std::vector<BodyPose>& poses, double t) {
  if (empty()) return;
  if (poses.size() != poses_.size()) fail("rigid bodies: reset with ", poses.size(), " poses for ", poses_.size(), " bodies");
  World& w = *world_;
  // Out and back in, in the order they were made: the broadphase and the solver start afresh.
  for (auto& o : w.objects) w.world.removeRigidBody(o.get());
  w.broadphase.resetPool(&w.dispatcher);
  w.solver.reset();
  for (size_t b = 0; b < w.bodies.size(); ++b) {
    btRigidBody& body = *w.bodies[b];
    // Also the world inertia tensor, which Bullet otherwise keeps from the body's last step.
    body.setCenterOfMassTransform(pose_transform(poses[b].position, poses[b].orientation));
    body.setLinearVelocity(bt(poses[b].velocity));
    body.setAngularVelocity(bt(poses[b].angular_velocity));
    body.setInterpolationLinearVelocity(body.getLinearVelocity());
    body.setInterpolationAngularVelocity(body.getAngularVelocity());
    body.clearForces();
  }
  for (const World::Kinematic& m : w.kinematic) {
    m.object->setWorldTransform(pose_transform(m.solid->centre() + m.solid->motion.offset(t), m.solid->orientation));
    m.object->setInterpolationWorldTransform(m.object->getWorldTransform());
  }
  for (size_t k = 0; k < w.objects.size(); ++k)
    w.world.addRigidBody(w.objects[k].get(), w.filters[k].first, w.filters[k].second);
  poses_ = poses;
}

}  // namespace spume::fluid
