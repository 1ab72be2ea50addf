#include "render/surface/triangle_mesh.h"

namespace spume {

void TriangleMesh::append(const TriangleMesh& other) {
  const uint32_t base = uint32_t(vertices.size());
  vertices.insert(vertices.end(), other.vertices.begin(), other.vertices.end());
  if (!other.normals.empty() || !normals.empty()) {
    normals.resize(base, Vec3f::UnitY());
    if (other.normals.empty()) normals.resize(vertices.size(), Vec3f::UnitY());
    else normals.insert(normals.end(), other.normals.begin(), other.normals.end());
  }
  for (uint32_t i : other.indices) indices.push_back(base + i);
}

}  // namespace spume
