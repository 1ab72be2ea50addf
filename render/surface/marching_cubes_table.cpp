#include "render/surface/marching_cubes_table.h"

#include <cassert>
#include <stdexcept>

namespace spume::mc {

// Edges along x start at the corners with x = 0 (0, 2, 4, 6), along y at y = 0, along z at z = 0.
const std::array<uint8_t, 12> kEdgeCorner = {0, 2, 4, 6, 0, 1, 4, 5, 0, 1, 2, 3};

namespace {

// Index of the edge joining two corners that differ in exactly one bit.
int edge_between(int c1, int c2) {
  const int diff = c1 ^ c2;
  const int axis = diff == 1 ? 0 : diff == 2 ? 1 : 2;
  const int lower = c1 & c2;
  for (int m = 0; m < 4; ++m)
    if (kEdgeCorner[axis * 4 + m] == lower) return axis * 4 + m;
  throw std::logic_error("marching cubes: corners do not share an edge");
}

// True when edge e lies in the cube face `axis` = `side`.
bool on_face(int e, int axis, int side) { return edge_axis(e) != axis && (kEdgeCorner[e] >> axis & 1) == side; }

// True when no triangle of the fan from loop[apex] has all three vertices in one cube face.
bool fan_is_clear(const int* loop, int n, int apex) {
  for (int i = 1; i + 1 < n; ++i) {
    const int a = loop[apex], b = loop[(apex + i) % n], c = loop[(apex + i + 1) % n];
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side)
        if (on_face(a, axis, side) && on_face(b, axis, side) && on_face(c, axis, side)) return false;
  }
  return true;
}

Case make_case(int mask, bool flip) {
  auto inside = [&](int corner) { return (mask >> corner & 1) != 0; };
  // next[e] = the crossing edge where the loop continues after e; -1 if e does not cross.
  int next[12];
  for (int& n : next) n = -1;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      // The face's corners counter-clockwise seen from outside the cube: with u = axis + 1, v = axis + 2
      // (u x v = +axis), the order (0,0) (1,0) (1,1) (0,1) is counter-clockwise seen from +axis.
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      int q[4] = {0, 1 << u, (1 << u) | (1 << v), 1 << v};
      for (int& c : q) c |= side << axis;
      if (side == 0) std::swap(q[1], q[3]);
      // Walk the face edges in that order: "enter" goes outside -> inside, "exit" inside -> outside.
      // Joining each enter to the next exit cuts off each run of inside corners separately.
      for (int k = 0; k < 4; ++k) {
        const int a = q[k], b = q[(k + 1) % 4];
        if (inside(a) || !inside(b)) continue;  // not an enter edge
        for (int j = 1; j < 4; ++j) {
          const int c = q[(k + j) % 4], d = q[(k + j + 1) % 4];
          if (inside(c) && !inside(d)) {
            next[edge_between(a, b)] = edge_between(c, d);
            break;
          }
        }
      }
    }
  // A crossing edge is an exit on one of its faces and an enter on the other, so next[] is a
  // permutation of the crossing edges: its cycles are the loops. Fan each loop.
  Case out;
  bool used[12] = {};
  for (int start = 0; start < 12; ++start) {
    if (next[start] < 0 || used[start]) continue;
    int loop[12], n = 0;
    for (int e = start; !used[e]; e = next[e]) {
      used[e] = true;
      loop[n++] = e;
    }
    // Fan from an apex chosen so that no triangle lies flat in a cube face: a loop can run along all
    // four crossing edges of an ambiguous face, and a flat triangle there would be produced again,
    // reversed, by the neighbouring cell.
    int apex = 0;
    while (apex < n && !fan_is_clear(loop, n, apex)) ++apex;
    if (apex == n) throw std::logic_error("marching cubes: no fan apex avoids the cube faces");
    for (int i = 1; i + 1 < n; ++i) {
      if (out.triangle_count >= kMaxTriangles) throw std::logic_error("marching cubes: too many triangles");
      auto& t = out.triangles[out.triangle_count++];
      t = {uint8_t(loop[apex]), uint8_t(loop[(apex + i) % n]), uint8_t(loop[(apex + i + 1) % n])};
      if (flip) std::swap(t[1], t[2]);
    }
  }
  return out;
}

// Winding of the rule above, measured on the case "only corner 0 inside": its triangle must face away
// from corner 0 (towards +x+y+z), where the field is lower.
bool needs_flip() {
  const Case c = make_case(1, false);
  auto mid = [](int e, int axis) {
    const int corner = kEdgeCorner[e];
    return float(corner >> axis & 1) + (edge_axis(e) == axis ? 0.5f : 0.0f);
  };
  float p[3][3];
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) p[i][a] = mid(c.triangles[0][i], a);
  float e1[3], e2[3];
  for (int a = 0; a < 3; ++a) e1[a] = p[1][a] - p[0][a], e2[a] = p[2][a] - p[0][a];
  const float nx = e1[1] * e2[2] - e1[2] * e2[1], ny = e1[2] * e2[0] - e1[0] * e2[2],
              nz = e1[0] * e2[1] - e1[1] * e2[0];
  return nx + ny + nz < 0;
}

std::array<Case, 256> make_table() {
  const bool flip = needs_flip();
  std::array<Case, 256> table;
  for (int mask = 0; mask < 256; ++mask) table[mask] = make_case(mask, flip);
  return table;
}

}  // namespace

const std::array<Case, 256>& cases() {
  static const std::array<Case, 256> table = make_table();
  return table;
}

}  // namespace spume::mc
