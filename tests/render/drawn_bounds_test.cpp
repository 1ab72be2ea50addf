// The box around a frame's drawn spheres against a plain loop over them, and the first bad particle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/volume/drawn_bounds.h"
#include "sim/core/error.h"

namespace spume {
namespace {

DiffuseFrame random_frame(size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-3.0f, 7.0f);
  DiffuseFrame f;
  f.resize(n);
  for (size_t i = 0; i < n; ++i) f.positions[i] = Vec3f(u(rng), u(rng), u(rng)), f.types[i] = DiffuseType(rng() % 3);
  return f;
}

std::string error_of(const DiffuseFrame& f, const std::array<float, kDiffuseTypeCount>& radius) {
  size_t count = 0;
  try {
    drawn_bounds(f, radius, count);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(DrawnBounds, TheBoxOfTheDrawnSpheresAndTheirCount) {
  // Sizes around the chunk and lane splits; foam not drawn, and its far-off particles left out.
  for (size_t n : {1ul, 7ul, 8ul, 9ul, 65'537ul, 300'001ul}) {
    DiffuseFrame f = random_frame(n, unsigned(n));
    for (size_t i = 0; i < n; i += 97)
      if (f.types[i] == DiffuseType::Foam) f.positions[i] = Vec3f(1e6f, -1e6f, INFINITY);
    const std::array<float, kDiffuseTypeCount> radius{0.25f, 0.0f, 0.5f};
    Vec3d lo = Vec3d::Constant(INFINITY), hi = Vec3d::Constant(-INFINITY);
    size_t expected = 0;
    for (size_t i = 0; i < n; ++i) {
      const double r = radius[size_t(f.types[i])];
      if (r == 0.0) continue;
      ++expected;
      for (int a = 0; a < 3; ++a)
        lo[a] = std::min(lo[a], double(f.positions[i][a]) - r), hi[a] = std::max(hi[a], double(f.positions[i][a]) + r);
    }
    size_t count = 0;
    const Aabb box = drawn_bounds(f, radius, count);
    EXPECT_EQ(count, expected) << n;
    if (expected == 0) continue;
    for (int a = 0; a < 3; ++a) {  // float sums of a float and r: within an ulp of the double ones
      EXPECT_NEAR(box.min[a], lo[a], 1e-6 * (1 + std::abs(lo[a]))) << n;
      EXPECT_NEAR(box.max[a], hi[a], 1e-6 * (1 + std::abs(hi[a]))) << n;
    }
  }
}

TEST(DrawnBounds, TheFirstBadParticleIsNamed) {
  const std::array<float, kDiffuseTypeCount> radius{0.1f, 0.0f, 0.1f};
  DiffuseFrame f = random_frame(200'000, 4);
  f.types[150'000] = DiffuseType(5);
  f.types[120'003] = DiffuseType::Bubble, f.positions[120'003].y() = NAN;
  f.types[90'000] = DiffuseType::Foam, f.positions[90'000].x() = NAN;  // not drawn: no matter
  EXPECT_NE(error_of(f, radius).find("particle 120003 "), std::string::npos) << error_of(f, radius);
  f.positions[120'003].y() = 0.0f;
  EXPECT_NE(error_of(f, radius).find("particle 150000 "), std::string::npos) << error_of(f, radius);
  f.types[150'000] = DiffuseType::Spray;
  EXPECT_EQ(error_of(f, radius), "");
}

}  // namespace
}  // namespace spume
