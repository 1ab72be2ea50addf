#pragma once
// The fluid particles of one cell's 3x3x3 block, copied into contiguous float arrays (structure of
// arrays) and padded to a multiple of kLanes with far-away points. Loops over it accumulate into
// kLanes independent partial sums, which the compiler turns into SIMD code; the sums are then added
// in a fixed order, so results stay bit-identical for any thread count.
#include <array>
#include <span>
#include <vector>

#include "sim/grid/neighbour_grid.h"

namespace spume {

constexpr size_t kLanes = 8;
// Padding coordinate: far beyond any support radius, so every weight is zero, yet small enough that
// loops which clamp squared distances keep every intermediate finite.
constexpr float kFarAway = 1e15f;

class BlockBuffer {
 public:
  // Gathers positions and, for each attribute array (indexed by sorted point), its three components.
  void gather(const NeighbourGrid& grid, uint32_t key, std::initializer_list<std::span<const Vec3f>> attributes = {});
  // The points of `source` (and their attributes) that lie in `box`, in source order, padded again.
  // Scanning this smaller block instead of the whole 3x3x3 one gives the same sums when the box holds
  // every point within h of the points to be summed for (the missing ones carry zero weight).
  void gather_within(const BlockBuffer& source, const Aabb& box);

  size_t size() const { return x_.size(); }  // a multiple of kLanes
  const float* x() const { return x_.data(); }
  const float* y() const { return y_.data(); }
  const float* z() const { return z_.data(); }
  // Component c (0..2) of attribute a, in the order given to gather().
  const float* attribute(size_t a, int c) const { return attributes_[a][size_t(c)].data(); }
  const uint32_t* sorted_index() const { return index_.data(); }  // padding: UINT32_MAX

 private:
  void resize(size_t n, size_t attribute_count);
  void pad(size_t used);

  std::vector<float> x_, y_, z_;
  std::vector<std::array<std::vector<float>, 3>> attributes_;
  std::vector<uint32_t> index_;
};

// Sum of kLanes partial sums in a fixed order.
inline float lane_sum(const float (&lanes)[kLanes]) {
  float s = 0.0f;
  for (size_t l = 0; l < kLanes; ++l) s += lanes[l];
  return s;
}

}  // namespace spume
