// count_types against a count by hand: over several of its fixed chunks, with bytes that are no type
// (3 and 255) left out, whatever the thread count.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>
#include <vector>

#include "sim/core/frames.h"
#include "sim/core/parallel.h"

namespace spume {
namespace {

TEST(CountTypes, EqualsACountByHandAndLeavesOutInvalidBytes) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> pick(0, 9);
  const uint8_t values[10] = {0, 0, 0, 1, 1, 2, 2, 2, 3, 255};
  for (size_t n : {size_t(0), size_t(1), size_t(65535), size_t(65536 * 3 + 17)}) {
    std::vector<DiffuseType> types(n);
    std::array<size_t, kDiffuseTypeCount> expected{};
    for (size_t i = 0; i < n; ++i) {
      const uint8_t v = values[pick(rng)];
      types[i] = DiffuseType(v);
      if (v < kDiffuseTypeCount) ++expected[v];
    }
    for (int threads : {1, 2}) {
      set_thread_count(threads);
      EXPECT_EQ(count_types(types), expected) << n << " particles, " << threads << " threads";
    }
    set_thread_count(0);
  }
}

}  // namespace
}  // namespace spume
