#pragma once
// Marching-cubes case table, generated at start-up from a rule rather than typed in, so it is correct
// by construction:
//  - On each cube face the iso-line joins the crossing edges so that every inside corner is cut off on
//    its own ("separate the inside corners" on ambiguous faces). The rule looks only at the face's four
//    corners, so the two cells sharing a face always agree: the mesh has no cracks.
//  - Face segments are oriented consistently and chained into closed loops per cell; each loop is
//    fanned into triangles. Triangles wind counter-clockwise seen from outside (the low-value side).
//
// Conventions. Corner n of a cell sits at offset (n & 1, n >> 1 & 1, n >> 2 & 1). Edge e runs along
// axis a = e / 4 from its lower corner kEdgeCorner[e] to kEdgeCorner[e] | (1 << a). A case index has
// bit n set when corner n is inside (value >= iso).
#include <array>
#include <cstdint>

namespace spume::mc {

constexpr int kMaxTriangles = 12;  // per case; the generator checks it

struct Case {
  uint8_t triangle_count = 0;
  std::array<std::array<uint8_t, 3>, kMaxTriangles> triangles{};  // edge indices
};

// Lower corner of each edge.
extern const std::array<uint8_t, 12> kEdgeCorner;
inline int edge_axis(int e) { return e >> 2; }

// The 256 cases (generated once, thread-safe).
const std::array<Case, 256>& cases();

}  // namespace spume::mc
