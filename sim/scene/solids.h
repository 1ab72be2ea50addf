#pragma once
// Static solids of a scene, as the diffuse model sees them: where diffuse particles may not go, and
// how many fluid neighbours a solid stands in for (MODEL.md §8.11, §8.12).
#include <vector>

#include "core/vec.h"

namespace spume {

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
};

class SolidSet {
 public:
  SolidSet() = default;
  explicit SolidSet(std::vector<Solid> solids) : solids_(std::move(solids)) {}
  bool empty() const { return solids_.empty(); }
  const std::vector<Solid>& solids() const { return solids_; }

  // Volume within distance h of p that lies inside solids, treating each nearby solid face as a plane
  // (exact for a flat wall, an approximation at edges and on curved obstacles), capped at the sphere.
  float solid_volume_within(const Vec3f& p, float h) const;

  // Moves p into free space if it is inside a solid, onto the surface plus `skin`, and removes the
  // velocity component pointing into the solid. Returns true if p was moved.
  bool push_out(Vec3f& p, Vec3f& v, float skin) const;

 private:
  std::vector<Solid> solids_;
};

}  // namespace spume
