// The in-place compaction of the diffuse columns (sim/diffuse/compaction.h): the same particles in
// the order asked for, through buffers lent for it and no second set of columns.
#include <gtest/gtest.h>

#include <numeric>

#include "sim/diffuse/compaction.h"

namespace spume {
namespace {

DiffuseFrame numbered_frame(size_t n) {
  DiffuseFrame f;
  f.index = 7, f.time = 0.25;
  f.resize(n);
  for (size_t i = 0; i < n; ++i) {
    f.ids[i] = 1000 + i;
    f.positions[i] = Vec3f(float(i), 0.5f * float(i), -float(i));
    f.velocities[i] = Vec3f(0.0f, float(i) + 0.25f, 1.0f);
    f.lifetimes[i] = 0.125f * float(i);
    f.types[i] = DiffuseType(i % 3);
  }
  return f;
}

// The buffers a compaction borrows, empty unless a test sizes them.
struct Lenders {
  std::vector<Vec3f> vectors;
  std::vector<float> floats;
  std::vector<uint64_t> ids;
  std::vector<DiffuseType> types;
  CompactionBuffers buffers() { return {vectors, floats, ids, types}; }
};

TEST(Compaction, KeepsTheParticlesAskedForInTheirNewOrder) {
  DiffuseFrame f = numbered_frame(6);
  Lenders lenders;
  lenders.vectors.assign(2, Vec3f::Constant(9.0f));  // smaller than needed: must grow
  const std::vector<uint32_t> order = {4, 0, 5, 2};  // 1 and 3 dropped
  compact(f, order, lenders.buffers());
  ASSERT_EQ(f.size(), 4u);
  ASSERT_EQ(f.ids.size(), 4u);
  ASSERT_EQ(f.velocities.size(), 4u);
  ASSERT_EQ(f.lifetimes.size(), 4u);
  ASSERT_EQ(f.types.size(), 4u);
  for (size_t k = 0; k < order.size(); ++k) {
    const size_t i = order[k];
    EXPECT_EQ(f.ids[k], 1000 + i);
    EXPECT_EQ(f.positions[k], Vec3f(float(i), 0.5f * float(i), -float(i)));
    EXPECT_EQ(f.velocities[k], Vec3f(0.0f, float(i) + 0.25f, 1.0f));
    EXPECT_EQ(f.lifetimes[k], 0.125f * float(i));
    EXPECT_EQ(f.types[k], DiffuseType(i % 3));
  }
  EXPECT_EQ(f.index, 7);
  EXPECT_EQ(f.time, 0.25);
}

TEST(Compaction, LeavesRoomForAnEighthMore) {
  DiffuseFrame f = numbered_frame(100);
  Lenders lenders;
  std::vector<uint32_t> order(80);
  std::iota(order.begin(), order.end(), 20u);
  compact(f, order, lenders.buffers());
  ASSERT_EQ(f.size(), 80u);
  // Gathered into fresh buffers sized for 80 + 80/8 particles.
  EXPECT_GE(f.lifetimes.capacity(), 90u);
  EXPECT_GE(f.ids.capacity(), 90u);
  EXPECT_GE(f.types.capacity(), 90u);
  EXPECT_EQ(f.positions[0], Vec3f(20.0f, 10.0f, -20.0f));
  EXPECT_EQ(f.positions[79], Vec3f(99.0f, 49.5f, -99.0f));
}

TEST(Compaction, LendsTheOldBuffersBackAndHoldsNoSecondSet) {
  DiffuseFrame f = numbered_frame(64);
  Lenders lenders;
  lenders.vectors.reserve(128);
  lenders.floats.reserve(128);
  const Vec3f* old_positions = f.positions.data();
  const Vec3f* old_velocities = f.velocities.data();
  const Vec3f* lent_vectors = lenders.vectors.data();
  const float* lent_floats = lenders.floats.data();
  const float* old_lifetimes = f.lifetimes.data();
  std::vector<uint32_t> order(56);  // 63 down to 8: room for 56 + 7 fits the old blocks of 64
  std::iota(order.rbegin(), order.rend(), 8u);
  compact(f, order, lenders.buffers());
  // Positions went into the lent array, velocities into the old positions' block: one spare block of
  // vectors served both, and the lender now holds the old velocities' block.
  EXPECT_EQ(f.positions.data(), lent_vectors);
  EXPECT_EQ(f.velocities.data(), old_positions);
  EXPECT_EQ(lenders.vectors.data(), old_velocities);
  EXPECT_EQ(f.lifetimes.data(), lent_floats);
  EXPECT_EQ(lenders.floats.data(), old_lifetimes);
  EXPECT_EQ(f.positions[0], Vec3f(63.0f, 31.5f, -63.0f));
  EXPECT_EQ(f.velocities[55], Vec3f(0.0f, 8.25f, 1.0f));
}

TEST(Compaction, AnEmptyOrderLeavesNoParticle) {
  DiffuseFrame f = numbered_frame(5);
  Lenders lenders;
  compact(f, std::span<const uint32_t>(), lenders.buffers());
  EXPECT_EQ(f.size(), 0u);
  EXPECT_EQ(f.ids.size(), 0u);
  EXPECT_EQ(f.types.size(), 0u);
}

}  // namespace
}  // namespace spume
