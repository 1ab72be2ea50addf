#pragma once
// The water surface's triangles handed to Embree as quads: two triangles that follow each other in the
// mesh and share an edge (marching cubes writes a cell's triangles together, so most do) become one
// quad, which halves the primitives Embree's BVH is built over (a third of the volume pass at the
// lighthouse's 1M triangles).
#include <cstdint>
#include <vector>

#include "render/surface/triangle_mesh.h"

namespace spume {

struct QuadPairs {
  // Four vertex indices a quad, (v0, v1, v2, v3). Embree splits a quad into the triangles
  // (v0, v1, v3) and (v2, v3, v1), along the diagonal v1-v3; those are `first` and `second` with the
  // mesh's own winding. A lone triangle repeats its last corner (v3 = v2), and its second half is empty.
  std::vector<uint32_t> corners;
  std::vector<uint32_t> first, second;  // the mesh's triangle behind each half; second == first when alone
  size_t size() const { return first.size(); }
  bool paired(size_t q) const { return first[q] != second[q]; }
};

// Triangles t and t + 1 are paired when they share an edge in opposite directions (the same side out)
// and their third corners differ; every triangle ends up in exactly one quad.
QuadPairs pair_triangles(const TriangleMesh& mesh);

}  // namespace spume
