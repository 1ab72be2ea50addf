// Triangles paired into Embree quads: Embree splits quad (v0, v1, v2, v3) into (v0, v1, v3) and
// (v2, v3, v1) (its documented convention), so each half must be the mesh's triangle with its winding.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include "render/volume/quad_pairs.h"

namespace spume {
namespace {

using Corners = std::array<uint32_t, 3>;

Corners triangle(const TriangleMesh& m, uint32_t t) { return {m.indices[3 * t], m.indices[3 * t + 1], m.indices[3 * t + 2]}; }

// The same triangle with the same winding: equal up to rotation.
bool same_winding(Corners a, const Corners& b) {
  for (int r = 0; r < 3; ++r) {
    if (a == b) return true;
    std::rotate(a.begin(), a.begin() + 1, a.end());
  }
  return false;
}

void expect_halves_are_the_triangles(const TriangleMesh& m, const QuadPairs& p) {
  ASSERT_EQ(p.corners.size(), 4 * p.size());
  std::vector<int> seen(m.triangle_count(), 0);
  for (size_t q = 0; q < p.size(); ++q) {
    const uint32_t* c = &p.corners[4 * q];
    EXPECT_TRUE(same_winding({c[0], c[1], c[3]}, triangle(m, p.first[q]))) << q;
    ++seen[p.first[q]];
    if (p.paired(q)) {
      EXPECT_TRUE(same_winding({c[2], c[3], c[1]}, triangle(m, p.second[q]))) << q;
      ++seen[p.second[q]];
    } else {
      EXPECT_EQ(c[3], c[2]) << q;  // Embree's lone triangle
    }
  }
  for (size_t t = 0; t < seen.size(); ++t) EXPECT_EQ(seen[t], 1) << "triangle " << t;
}

TEST(QuadPairs, AStripOfSquaresPairsEveryTriangle) {
  // A row of unit squares, each split along a diagonal into two counter-clockwise triangles, with the
  // diagonal and the triangles' order changing from square to square.
  TriangleMesh m;
  const int squares = 6;
  for (int i = 0; i <= squares; ++i) m.vertices.push_back(Vec3f(float(i), 0, 0)), m.vertices.push_back(Vec3f(float(i), 1, 0));
  for (uint32_t i = 0; i < uint32_t(squares); ++i) {
    const uint32_t a = 2 * i, b = 2 * i + 2, c = 2 * i + 3, d = 2 * i + 1;  // counter-clockwise square
    std::vector<uint32_t> t = i % 2 ? std::vector<uint32_t>{a, b, c, a, c, d} : std::vector<uint32_t>{b, c, d, b, d, a};
    if (i % 3 == 2) std::rotate(t.begin(), t.begin() + 3, t.end());  // the other triangle first
    m.indices.insert(m.indices.end(), t.begin(), t.end());
  }
  const QuadPairs p = pair_triangles(m);
  EXPECT_EQ(p.size(), size_t(squares));
  for (size_t q = 0; q < p.size(); ++q) EXPECT_TRUE(p.paired(q));
  expect_halves_are_the_triangles(m, p);
}

TEST(QuadPairs, TrianglesThatCannotPairStayAlone) {
  TriangleMesh m;
  m.vertices = {Vec3f(0, 0, 0), Vec3f(1, 0, 0), Vec3f(1, 1, 0), Vec3f(0, 1, 0), Vec3f(5, 5, 5)};
  m.indices = {0, 1, 2,   // has edge 2 -> 0 ...
               2, 0, 3,   // ... and so does this one: the same direction, so its other side is out
               3, 0, 2,   // the one before facing the other way: the same corners, never a quad
               1, 2, 4};  // the last: nothing after it
  const QuadPairs p = pair_triangles(m);
  ASSERT_EQ(p.size(), 4u);
  for (size_t q = 0; q < p.size(); ++q) EXPECT_FALSE(p.paired(q)) << q;
  expect_halves_are_the_triangles(m, p);
}

TEST(QuadPairs, ARandomMeshKeepsEveryTriangleOnce) {
  // A fan of random triangles around shared corners: some consecutive ones share an edge either way.
  std::mt19937 rng(3);
  TriangleMesh m;
  for (int i = 0; i < 40; ++i) m.vertices.push_back(Vec3f(float(rng() % 100), float(rng() % 100), 0));
  for (int t = 0; t < 3000; ++t) {
    uint32_t a = rng() % 40, b = rng() % 40, c = rng() % 40;
    while (b == a) b = rng() % 40;
    while (c == a || c == b) c = rng() % 40;
    m.indices.insert(m.indices.end(), {a, b, c});
  }
  const QuadPairs p = pair_triangles(m);
  expect_halves_are_the_triangles(m, p);
  EXPECT_LT(p.size(), m.triangle_count());  // some paired
}

}  // namespace
}  // namespace spume
