#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include "sim/core/parallel.h"
#include "sim/grid/neighbour_grid.h"
#include "sim/core/radix_sort.h"

namespace spume {
namespace {

std::vector<Vec3f> random_points(size_t n, float extent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-extent, extent);
  std::vector<Vec3f> p(n);
  for (auto& x : p) x = Vec3f(u(rng), u(rng), u(rng));
  return p;
}

// Brute force over all pairs is the independent reference.
TEST(NeighbourGrid, FindsExactlyThePointsWithinTheRadius) {
  const auto points = random_points(3000, 1.0f, 1);
  NeighbourGrid grid;
  grid.build(points, 0.15f);
  const auto queries = random_points(300, 1.3f, 2);  // some outside the points' box
  for (const Vec3f& q : queries) {
    for (float radius : {0.15f, 0.07f}) {
      std::vector<uint32_t> expected, found;
      for (uint32_t i = 0; i < points.size(); ++i)
        if ((points[i] - q).squaredNorm() <= radius * radius) expected.push_back(i);
      grid.for_each_neighbour(q, radius, [&](uint32_t sj, float) { found.push_back(grid.sorted_to_original()[sj]); });
      std::sort(found.begin(), found.end());
      ASSERT_EQ(found, expected);
    }
  }
}

TEST(NeighbourGrid, SortedOrderIsAPermutationAndIndependentOfThreadCount) {
  const auto points = random_points(20000, 2.0f, 3);
  set_thread_count(1);
  NeighbourGrid one;
  one.build(points, 0.2f);
  set_thread_count(2);
  NeighbourGrid two;
  two.build(points, 0.2f);
  set_thread_count(0);
  std::vector<uint32_t> order(one.sorted_to_original().begin(), one.sorted_to_original().end());
  EXPECT_TRUE(std::equal(order.begin(), order.end(), two.sorted_to_original().begin()));
  std::sort(order.begin(), order.end());
  for (uint32_t i = 0; i < order.size(); ++i) ASSERT_EQ(order[i], i);
}

TEST(NeighbourGrid, FarOutlierKeepsQueriesExactWithACoarserGrid) {
  auto points = random_points(500, 0.5f, 4);
  points.push_back(Vec3f(1e5f, 0.0f, 0.0f));  // would need 1e18 cells at h = 0.05
  NeighbourGrid grid;
  grid.build(points, 0.05f);
  EXPECT_GE(grid.cell_size(), 0.05f);
  int found = 0;
  grid.for_each_neighbour(Vec3f(1e5f, 0.01f, 0.0f), 0.05f, [&](uint32_t, float) { ++found; });
  EXPECT_EQ(found, 1);
}

// The half of its cell a point lies in, told apart without the grid's origin: a point in the upper
// half along an axis stays in its cell when moved back by half a cell; one in the lower half leaves it.
TEST(NeighbourGrid, OctantKeysNameThePointsCellAndItsHalf) {
  const auto points = random_points(2000, 1.0f, 7);
  NeighbourGrid grid;
  grid.build(points, 0.1f);
  const auto queries = random_points(20000, 1.4f, 8);  // some beyond the grid's box
  std::vector<uint32_t> keys(queries.size());
  grid.octant_keys(queries, keys);
  const float half = 0.5f * grid.cell_size();
  size_t inside = 0, upper[3] = {};
  for (size_t i = 0; i < queries.size(); ++i) {
    const uint32_t cell = grid.key_of(queries[i]);
    if (cell == NeighbourGrid::kOutside) {
      ASSERT_EQ(keys[i], NeighbourGrid::kOutside) << i;
      continue;
    }
    ++inside;
    ASSERT_EQ(keys[i] >> 3, cell) << i;
    for (int a = 0; a < 3; ++a) {
      Vec3f back = queries[i];
      back[a] -= half;
      const bool in_upper_half = grid.key_of(back) == cell;
      ASSERT_EQ(((keys[i] >> a) & 1u) != 0, in_upper_half) << i << " axis " << a;
      upper[a] += in_upper_half;
    }
  }
  // Both outcomes occur, so the test can fail either way.
  EXPECT_GT(inside, 5000u);
  EXPECT_LT(inside, queries.size());
  for (size_t u : upper) {
    EXPECT_GT(u, inside / 3);
    EXPECT_LT(u, 2 * inside / 3);
  }

  NeighbourGrid empty;
  empty.build({}, 1.0f);
  empty.octant_keys(queries, keys);
  EXPECT_EQ(std::count(keys.begin(), keys.end(), NeighbourGrid::kOutside), std::ptrdiff_t(keys.size()));
}

TEST(NeighbourGrid, EmptyGridHasNoNeighbours) {
  NeighbourGrid grid;
  grid.build({}, 1.0f);
  EXPECT_EQ(grid.key_of(Vec3f::Zero()), NeighbourGrid::kOutside);
}

// The indices of `keys` in stable sorted order, by the standard library: what a radix sort must give.
std::vector<uint32_t> stable_sorted_indices(const std::vector<uint32_t>& keys) {
  std::vector<uint32_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  return order;
}

TEST(RadixSort, IsAStableSortByKey) {
  std::mt19937 rng(5);
  std::vector<uint32_t> keys(100000);
  for (auto& k : keys) k = rng() % 5000;
  const auto order = radix_sort_indices(keys, 13);
  for (size_t i = 1; i < order.size(); ++i) {
    ASSERT_LE(keys[order[i - 1]], keys[order[i]]);
    if (keys[order[i - 1]] == keys[order[i]]) {
      ASSERT_LT(order[i - 1], order[i]);  // stable
    }
  }
}

TEST(RadixSort, ManyChunksMatchStdStableSortForOneAndTwoThreads) {
  // 700k keys: several of the sort's 64k-element chunks, and 20 bits (two passes of 10).
  std::mt19937 rng(6);
  std::vector<uint32_t> keys(700000);
  for (auto& k : keys) k = rng() % (1u << 20);
  for (size_t i = 1000; i < 300000; ++i) keys[i] = keys[i - 1000];  // long runs of equal keys
  const std::vector<uint32_t> expected = stable_sorted_indices(keys);
  for (int threads : {1, 2}) {
    set_thread_count(threads);
    RadixSorter sorter;
    sorter.sort(keys, 20);
    ASSERT_EQ(sorter.order(), expected) << threads;
    for (size_t i = 0; i < keys.size(); ++i) ASSERT_EQ(sorter.sorted_keys()[i], keys[expected[i]]);
    sorter.sort(std::vector<uint32_t>(keys.begin(), keys.begin() + 10), 20);  // reused buffers shrink
    ASSERT_EQ(sorter.order().size(), 10u);
  }
  set_thread_count(0);
}

TEST(RadixSort, KeysWrittenIntoTheSorterSortAsTheCallersDo) {
  // 700k keys of 20 bits (two passes of 10) and of 31 bits (three passes of 11): the sorted keys end in
  // the input's own buffer after an even number of passes, in the other one after an odd number.
  std::mt19937 rng(7);
  for (int bits : {20, 31}) {
    std::vector<uint32_t> keys(700000);
    for (auto& k : keys) k = uint32_t(rng()) & ((1u << bits) - 1);
    for (size_t i = 500; i < 200000; ++i) keys[i] = keys[i - 500];  // runs of equal keys
    const std::vector<uint32_t> expected = stable_sorted_indices(keys);
    RadixSorter sorter;
    for (int round = 0; round < 2; ++round) {  // the second round reuses the buffers the first left
      sorter.input_keys() = keys;
      sorter.sort_input_keys(bits);
      ASSERT_EQ(sorter.order(), expected) << bits << " " << round;
      for (size_t i = 0; i < keys.size(); ++i) ASSERT_EQ(sorter.sorted_keys()[i], keys[expected[i]]);
    }
  }
}

TEST(ParallelSelect, KeepsTheSelectedIndicesInOrderForOneAndTwoThreads) {
  const size_t n = 1000003;  // many chunks, the last one short
  std::vector<size_t> expected;
  for (size_t i = 0; i < n; ++i)
    if (i % 7 == 3 || (i > 500000 && i < 500100)) expected.push_back(i);
  for (int threads : {1, 2}) {
    set_thread_count(threads);
    std::vector<size_t> got(n, SIZE_MAX);
    const size_t kept = parallel_select(
        n, [](size_t i) { return i % 7 == 3 || (i > 500000 && i < 500100); }, [&](size_t i, size_t k) { got[k] = i; });
    ASSERT_EQ(kept, expected.size());
    got.resize(kept);
    ASSERT_EQ(got, expected) << threads;
  }
  set_thread_count(0);
  EXPECT_EQ(parallel_select(0, [](size_t) { return true; }, [](size_t, size_t) {}), 0u);
}

}  // namespace
}  // namespace spume
