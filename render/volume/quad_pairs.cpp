#include "render/volume/quad_pairs.h"

namespace spume {
namespace {

// The quad of triangles a and b (three corners each) when b holds one of a's edges reversed, or false.
// With a rotated to (p0, p1, p2) so that the shared edge is p2 -> p0, b reads (p0, p2, q), and the quad
// (p1, p2, q, p0) splits into (p1, p2, p0) and (q, p0, p2): a and b, each in its own winding.
bool as_quad(const uint32_t* a, const uint32_t* b, uint32_t quad[4]) {
  for (int r = 0; r < 3; ++r) {
    const uint32_t p0 = a[r], p1 = a[(r + 1) % 3], p2 = a[(r + 2) % 3];
    for (int s = 0; s < 3; ++s)
      if (b[s] == p0 && b[(s + 1) % 3] == p2) {
        const uint32_t q = b[(s + 2) % 3];
        if (q == p1) return false;  // the same triangle facing the other way
        quad[0] = p1, quad[1] = p2, quad[2] = q, quad[3] = p0;
        return true;
      }
  }
  return false;
}

}  // namespace

QuadPairs pair_triangles(const TriangleMesh& mesh) {
  const size_t n = mesh.triangle_count();
  const uint32_t* index = mesh.indices.data();
  QuadPairs pairs;
  pairs.corners.reserve(4 * (n / 2 + n / 8));
  pairs.first.reserve(n / 2 + n / 8);
  pairs.second.reserve(n / 2 + n / 8);
  for (size_t t = 0; t < n;) {
    uint32_t quad[4];
    if (t + 1 < n && as_quad(index + 3 * t, index + 3 * t + 3, quad)) {
      pairs.corners.insert(pairs.corners.end(), quad, quad + 4);
      pairs.first.push_back(uint32_t(t)), pairs.second.push_back(uint32_t(t + 1));
      t += 2;
    } else {
      const uint32_t* a = index + 3 * t;
      pairs.corners.insert(pairs.corners.end(), {a[0], a[1], a[2], a[2]});
      pairs.first.push_back(uint32_t(t)), pairs.second.push_back(uint32_t(t));
      t += 1;
    }
  }
  return pairs;
}

}  // namespace spume
