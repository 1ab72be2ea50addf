#include <gtest/gtest.h>

#include <cmath>

#include "sim/core/rng.h"

namespace spume {
namespace {

// Known-answer vectors published with Random123 (kat_vectors, philox4x32 with 10 rounds).
TEST(Philox, MatchesPublishedKnownAnswers) {
  EXPECT_EQ(philox4x32({0, 0, 0, 0}, {0, 0}), (std::array<uint32_t, 4>{0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}));
  EXPECT_EQ(philox4x32({0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff}, {0xffffffff, 0xffffffff}),
            (std::array<uint32_t, 4>{0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}));
  EXPECT_EQ(philox4x32({0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344}, {0xa4093822, 0x299f31d0}),
            (std::array<uint32_t, 4>{0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}));
}

TEST(Philox, UniformsAreInUnitIntervalWithMeanAndVarianceOfUniform) {
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const auto u = random_uniform4({7, RandomPurpose::Test, 3, uint64_t(i), 0});
    for (float x : u) {
      ASSERT_GE(x, 0.0f);
      ASSERT_LT(x, 1.0f);
      sum += x, sum2 += double(x) * x;
    }
  }
  const double m = sum / (4.0 * n), var = sum2 / (4.0 * n) - m * m;
  // Standard error of the mean of 800k uniforms is 0.29/sqrt(800k) = 3.2e-4; allow 5 sigma.
  EXPECT_NEAR(m, 0.5, 1.6e-3);
  EXPECT_NEAR(var, 1.0 / 12.0, 1e-3);
}

TEST(Philox, StreamsDependOnEveryKeyPart) {
  const RandomKey base{1, RandomPurpose::CylinderSample, 2, 3, 4};
  const auto reference = random_bits(base);
  RandomKey k = base;
  k.seed = 2;
  EXPECT_NE(random_bits(k), reference);
  k = base, k.purpose = RandomPurpose::EmissionRounding;
  EXPECT_NE(random_bits(k), reference);
  k = base, k.step = 5;
  EXPECT_NE(random_bits(k), reference);
  k = base, k.item = uint64_t(3) | (uint64_t(1) << 40);
  EXPECT_NE(random_bits(k), reference);
  k = base, k.sample = 9;
  EXPECT_NE(random_bits(k), reference);
  EXPECT_EQ(random_bits(base), reference);
}

}  // namespace
}  // namespace spume
