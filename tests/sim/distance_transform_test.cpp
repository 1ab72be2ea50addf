// The exact distance transform against the brute-force minimum over the seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sim/grid/distance_transform.h"

namespace spume {
namespace {

TEST(DistanceTransform, MatchesTheNearestSeedByBruteForce) {
  const std::array<int64_t, 3> dims = {13, 9, 7};
  const size_t cells = size_t(dims[0] * dims[1] * dims[2]);
  std::mt19937 rng(3);
  for (const int seeds : {1, 5, 40}) {
    std::vector<uint8_t> seed(cells, 0);
    for (int k = 0; k < seeds; ++k) seed[rng() % cells] = 1;
    const std::vector<float> d2 = squared_distance_to_seeds(seed, dims);
    ASSERT_EQ(d2.size(), cells);
    for (size_t c = 0; c < cells; ++c) {
      const int64_t x = int64_t(c) % dims[0], y = (int64_t(c) / dims[0]) % dims[1], z = int64_t(c) / (dims[0] * dims[1]);
      int64_t best = INT64_MAX;
      for (size_t s = 0; s < cells; ++s) {
        if (!seed[s]) continue;
        const int64_t sx = int64_t(s) % dims[0], sy = (int64_t(s) / dims[0]) % dims[1], sz = int64_t(s) / (dims[0] * dims[1]);
        best = std::min(best, (x - sx) * (x - sx) + (y - sy) * (y - sy) + (z - sz) * (z - sz));
      }
      ASSERT_EQ(d2[c], float(best)) << seeds << " seeds, cell " << x << " " << y << " " << z;
    }
  }
}

TEST(DistanceTransform, NoSeedIsInfinitelyFar) {
  const std::vector<float> d2 = squared_distance_to_seeds(std::vector<uint8_t>(24, 0), {4, 3, 2});
  for (const float d : d2) EXPECT_TRUE(std::isinf(d));
}

}  // namespace
}  // namespace spume
