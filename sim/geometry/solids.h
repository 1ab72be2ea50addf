#pragma once
// Solids of a scene, as the diffuse model and the fluid solver see them: where particles may not go,
// and how many fluid neighbours a solid stands in for (MODEL.md §8.11, §8.12). A solid is
//  - static;
//  - KINEMATIC: a prescribed translation over time (a wave-making piston or flap, a hull on a path),
//    translation only (a box may have a fixed orientation, which its motion keeps);
//  - DYNAMIC (boxes and spheres): a rigid body two-way coupled with the fluid solver, which owns its
//    trajectory (fluid/rigid_bodies.h). A SolidSet holds such a body at its initial pose; the pose at
//    a later time comes from the solver (FluidSolver::body_poses) and is applied with `posed`.
// Boxes may be rotated (orientation about their centre); tanks are axis-aligned.
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "sim/core/vec.h"
#include "sim/keys/scene_keys.h"

namespace spume {

using Quatf = Eigen::Quaternionf;

// A prescribed translation of a solid, added to its geometry as given in the scene.
//  - None: static.
//  - Keyframes: piecewise-linear offsets through (times[k], offsets[k]); held at the first offset
//    before times[0] and at the last after times.back(). Velocity is the slope of the segment holding
//    t (zero outside the keyframes). Times strictly increase.
//  - Sine: offset(t) = amplitude * axis * sin(2 pi frequency (t - start) + phase) for t >= start, and
//    the value at `start` before it (so the solid rests until it starts). Velocity is the derivative.
struct Motion {
  enum class Kind { None, Keyframes, Sine };
  Kind kind = Kind::None;
  std::vector<double> times;   // s, Keyframes
  std::vector<Vec3f> offsets;  // m, Keyframes
  Vec3f axis = declared_vec3<Vec3f>(keys::solids::motion_axis);  // unit vector, Sine
  float amplitude = float(keys::solids::motion_amplitude.value[0]);  // m, Sine
  float frequency = float(keys::solids::motion_frequency.value[0]);  // Hz, Sine
  float phase = float(keys::solids::motion_phase.value[0]);  // rad, Sine
  double start = keys::solids::motion_start.value[0];  // s, Sine

  bool moving() const { return kind != Kind::None; }
  Vec3f offset(double t) const;    // m
  Vec3f velocity(double t) const;  // m/s
  // Throws Error (prefixed by `where`) for unsorted keyframes, a non-unit axis, negative values...
  void validate(const char* where) const;
};

// Mass properties of a dynamic solid (a rigid body simulated with Bullet, pushed by the fluid).
struct Dynamics {
  bool enabled = false;
  float density = 0.0f;   // kg/m^3; the mass is density x volume unless `mass` is set
  float mass = 0.0f;      // kg; > 0 overrides density
  float friction = float(keys::solids::friction.value[0]);  // Coulomb coefficient in contacts with other solids
};

// Where a dynamic solid is at some time: its centre (box centre, sphere centre), orientation and
// velocities. `solid` indexes the SolidSet it belongs to.
struct BodyPose {
  uint32_t solid = 0;
  Vec3f position = Vec3f::Zero();             // m, centre of mass
  Quatf orientation = Quatf::Identity();      // body frame -> world
  Vec3f velocity = Vec3f::Zero();             // m/s, of the centre
  Vec3f angular_velocity = Vec3f::Zero();     // rad/s, world frame
};

struct Solid {
  enum class Kind {
    Tank,    // hollow box: free space inside, walls on its faces (the top may be open)
    Box,     // solid box obstacle: free space outside
    Sphere,  // solid sphere obstacle: free space outside
  };
  Kind kind = Kind::Tank;
  Vec3f min = Vec3f::Zero(), max = Vec3f::Zero();  // Tank, Box
  Vec3f center = Vec3f::Zero();                    // Sphere
  float radius = 0.0f;                             // Sphere
  bool open_top = keys::solids::open_top.value[0] != 0.0;  // Tank: no wall at max along "up"
  int up_axis = 1;                                 // Tank: which axis is up (opposite gravity)
  // Tank: m. Beyond its walls by more than this is the world outside the tank, where spray thrown
  // over the rim falls. Infinite: nothing is outside (every point beyond a wall is in it).
  float wall_thickness = std::numeric_limits<float>::infinity();
  // Box, Sphere: rotation about the centre, body frame -> world; the box's min/max are its extent in
  // its own frame (centred on (min + max) / 2). Tanks must keep the identity.
  Quatf orientation = Quatf::Identity();
  Motion motion;                                   // kinematic translation (None: static)
  Dynamics dynamics;                               // enabled: a rigid body (motion must be None)
  Vec3f velocity = Vec3f::Zero();                  // m/s: set on snapshots (at_time, posed)
  Vec3f angular_velocity = Vec3f::Zero();          // rad/s, world frame: set on snapshots (posed)

  Solid translated(const Vec3f& offset) const;  // the same solid moved rigidly by offset
  Vec3f centre() const;                         // Box: (min + max) / 2, Sphere: center, Tank: (min + max) / 2
  bool rotated() const;                         // orientation is not exactly the identity
  float volume() const;                         // m^3 (Box, Sphere)
  // Velocity of the solid's material at world point p: velocity + angular_velocity x (p - centre).
  Vec3f velocity_at(const Vec3f& p) const;
};

// The ground under the tanks: the lowest tank floor, across their common up axis. Spray thrown over
// a rim falls outside the tanks until it reaches it.
struct GroundPlane {
  int up_axis = 1;
  float level = 0.0f;
};

class SolidSet {
 public:
  SolidSet() = default;
  explicit SolidSet(std::vector<Solid> solids);
  bool empty() const { return solids_.empty(); }
  const std::vector<Solid>& solids() const { return solids_; }
  bool any_moving() const;   // a kinematic motion or a dynamic body
  bool any_dynamic() const;
  // None without a tank, or when the tanks disagree on which axis is up.
  std::optional<GroundPlane> ground_below_tanks() const;

  // The solids at time t (s): each moved by its motion's offset(t), with `velocity` set to the
  // motion's velocity at t and the motion itself cleared, so the snapshot is a static set that
  // remembers how fast each solid moves (push_out then works relative to the moving wall).
  // Dynamic bodies stay at their initial pose (see `posed`).
  SolidSet at_time(double t) const;

  // This set with each listed dynamic body moved to its pose (centre, orientation, velocities); the
  // bodies keep their Dynamics. Throws Error if a pose names a solid that is not dynamic.
  SolidSet posed(const std::vector<BodyPose>& poses) const;

  // Throws Error naming the solid for what the solvers cannot handle: bad motions, a rotated tank, a
  // dynamic tank or a dynamic solid with a motion, non-positive mass or density, bad friction.
  void validate() const;

  // Moves p into free space if it is inside a solid, onto the surface plus `skin` (at least a few
  // ulps of p's largest coordinate, so that it ends outside however far from the origin), and removes the
  // velocity component pointing into the solid (relative to the solid's velocity at p, see
  // Solid::velocity_at; zero for static solids). Returns true if p was moved. Uses the geometry as
  // stored; a rotated box pushes along its own face normals. Where solids touch, a box is left by
  // its shallowest face that opens into free space, and up to three passes settle the point.
  bool push_out(Vec3f& p, Vec3f& v, float skin) const;

  // A step from `from` to p that crosses a tank's wall or floor below the rim ends inside the tank,
  // `skin` from the wall (as in push_out), with the velocity into the wall removed (relative to the
  // wall): fast spray would otherwise pass through a wall thinner than its step and be lost outside.
  // The step stops at the first wall it meets and slides along it (its motion along the wall kept),
  // so a step across an edge or into a corner stops at every wall it meets, in the order it meets
  // them. A step that crosses a wall's plane above an open rim goes over it. Returns true if p was
  // moved. Call before push_out, which sees only where a step ends.
  bool stop_at_tank_walls(const Vec3f& from, Vec3f& p, Vec3f& v, float skin) const;

  // True when p is inside a solid (or outside a tank's walls): push_out would move it.
  bool inside(const Vec3f& p) const;
  // True when p is inside a box or sphere or within `reach` (> 0, m) of one (Euclidean distance to
  // the solid as stored, rotated boxes in their own frame). Tanks are not counted.
  bool obstacle_within(const Vec3f& p, float reach) const;

  // Whether p lies more than `reach` (>= 0) outside solid i's bounding box: then no ball of radius
  // `reach` around p meets that solid, and the exact tests can be skipped. A broad phase for the
  // per-particle loops, where most particles are far from most solids. The boxes are widened beyond
  // the rounding of the exact tests (and a rotation's quaternion off unit length by up to 1e-4), so
  // skipping a solid it calls far never changes a result. Never true for a tank (free space inside).
  bool far_from(size_t i, const Vec3f& p, float reach) const {
    const Aabb& b = bounds_[i];
    const float r = reach * 1.001f;
    return p.x() < b.min.x() - r || p.y() < b.min.y() - r || p.z() < b.min.z() - r || p.x() > b.max.x() + r ||
           p.y() > b.max.y() + r || p.z() > b.max.z() + r;
  }
  // The box far_from tests against: solid i's bounding box, widened as described there (infinite for a tank).
  const Aabb& broad_bounds(size_t i) const { return bounds_[i]; }

 private:
  void bound();  // bounds_ from solids_
  bool inside_other_than(const Vec3f& p, const Solid& skip) const;
  // If p is inside box s: the face to leave by (outward normal, depth of p below it), the shallowest
  // one whose exit point (plus skin) is not inside another solid.
  bool box_exit(const Solid& s, const Vec3f& p, float skin, Vec3f& normal, float& depth) const;

  std::vector<Solid> solids_;
  std::vector<Aabb> bounds_;  // per solid, widened (far_from); infinite for tanks
};

}  // namespace spume
