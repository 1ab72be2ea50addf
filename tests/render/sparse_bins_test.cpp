// Points binned by cell against a map built point by point: every occupied cell once, ascending, each
// holding exactly its points in input order. Over a compact box (sorted by radix) and over one of more
// than 2^32 cells (sorted by comparison).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "render/surface/sparse_bins.h"

namespace spume {
namespace {

void expect_binned(const std::vector<Vec3f>& points, const Vec3f& origin, float cell) {
  std::map<uint64_t, std::vector<uint32_t>> expected;
  for (uint32_t i = 0; i < points.size(); ++i) {
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = int(std::floor((points[i][a] - origin[a]) / cell));
    expected[SparseBins::pack(c[0], c[1], c[2])].push_back(i);
  }
  SparseBins bins;
  bins.build(points, origin, cell);
  ASSERT_EQ(bins.cell_count(), expected.size());
  size_t c = 0;
  for (const auto& [key, indices] : expected) {
    ASSERT_EQ(bins.key(c), key) << c;
    const auto got = bins.indices(c);
    ASSERT_EQ(std::vector<uint32_t>(got.begin(), got.end()), indices) << c;
    const auto at = bins.points(c);
    for (size_t k = 0; k < at.size(); ++k) ASSERT_EQ(at[k], points[indices[k]]);
    ++c;
  }
}

std::vector<Vec3f> random_points(size_t n, float extent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, extent);
  std::vector<Vec3f> p(n);
  for (auto& x : p) x = Vec3f(u(rng), u(rng), u(rng));
  return p;
}

TEST(SparseBins, ACompactBoxHoldsEveryPointInItsCellInInputOrder) {
  expect_binned(random_points(50'000, 1.0f, 1), Vec3f::Zero(), 0.05f);  // 20^3 cells, ~6 points each
  expect_binned(random_points(3, 1.0f, 2), Vec3f::Zero(), 0.05f);
}

TEST(SparseBins, ABoxOfMoreThan2To32CellsGivesTheSameBinning) {
  // A cloud and a few points 3000 cells away on every axis: 3001^3 cells, more than 2^32.
  std::vector<Vec3f> points = random_points(20'000, 1.0f, 3);
  for (int k = 0; k < 5; ++k) points.insert(points.begin() + 1000 * k, Vec3f(150.0f, 150.0f + 0.01f * k, 150.0f));
  expect_binned(points, Vec3f::Zero(), 0.05f);
}

}  // namespace
}  // namespace spume
