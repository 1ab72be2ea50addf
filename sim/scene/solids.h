#pragma once
// Solids of a scene, as the diffuse model and the fluid solver see them: where particles may not go,
// and how many fluid neighbours a solid stands in for (MODEL.md §8.11, §8.12). Solids are static or
// KINEMATIC: a prescribed translation over time (a wave-making piston or flap, a hull on a path).
// Rotation is not supported; dynamic (two-way coupled) bodies are not part of this header.
#include <vector>

#include "core/vec.h"

namespace spume {

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
  Vec3f axis = Vec3f::UnitX(); // unit vector, Sine
  float amplitude = 0.0f;      // m, Sine
  float frequency = 0.0f;      // Hz, Sine
  float phase = 0.0f;          // rad, Sine
  double start = 0.0;          // s, Sine

  bool moving() const { return kind != Kind::None; }
  Vec3f offset(double t) const;    // m
  Vec3f velocity(double t) const;  // m/s
  // Throws Error (prefixed by `where`) for unsorted keyframes, a non-unit axis, negative values...
  void validate(const char* where) const;
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
  bool open_top = true;                            // Tank: no wall at max along "up"
  int up_axis = 1;                                 // Tank: which axis is up (opposite gravity)
  Motion motion;                                   // kinematic translation (None: static)
  Vec3f velocity = Vec3f::Zero();                  // m/s: set on snapshots from SolidSet::at_time

  Solid translated(const Vec3f& offset) const;  // the same solid moved rigidly by offset
};

class SolidSet {
 public:
  SolidSet() = default;
  explicit SolidSet(std::vector<Solid> solids) : solids_(std::move(solids)) {}
  bool empty() const { return solids_.empty(); }
  const std::vector<Solid>& solids() const { return solids_; }
  bool any_moving() const;

  // The solids at time t (s): each moved by its motion's offset(t), with `velocity` set to the
  // motion's velocity at t and the motion itself cleared, so the snapshot is a static set that
  // remembers how fast each solid moves (push_out then works relative to the moving wall).
  SolidSet at_time(double t) const;

  // Volume within distance h of p that lies inside solids, treating each nearby solid face as a plane
  // (exact for a flat wall, an approximation at edges and on curved obstacles), capped at the sphere.
  // Uses the geometry as stored (call on at_time(t) for moving solids).
  float solid_volume_within(const Vec3f& p, float h) const;

  // Moves p into free space if it is inside a solid, onto the surface plus `skin`, and removes the
  // velocity component pointing into the solid (relative to the solid's `velocity`, zero for static
  // solids). Returns true if p was moved. Uses the geometry as stored.
  bool push_out(Vec3f& p, Vec3f& v, float skin) const;

  // True when p is inside a solid (or outside a tank's walls): push_out would move it.
  bool inside(const Vec3f& p) const;

 private:
  std::vector<Solid> solids_;
};

}  // namespace spume
