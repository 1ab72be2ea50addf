#pragma once
// A triangle mesh as plain arrays: the reconstructed fluid surface and the scene's solids, shared by
// the OSMesa pass (drawn) and the Embree pass (traced).
#include <cstdint>
#include <vector>

#include "sim/core/vec.h"

namespace spume {

struct TriangleMesh {
  std::vector<Vec3f> vertices;   // m
  std::vector<Vec3f> normals;    // unit, per vertex (smooth shading); may be empty
  std::vector<uint32_t> indices; // three per triangle, counter-clockwise seen from outside

  size_t triangle_count() const { return indices.size() / 3; }
  bool empty() const { return indices.empty(); }
  void append(const TriangleMesh& other);
};

}  // namespace spume
