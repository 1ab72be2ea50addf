#pragma once
// Points binned into cubic cells on a lattice anchored at `origin`, storing only occupied cells. The
// surface reconstruction's own spatial index (render/ must not link the simulator's neighbour grid).
// A sorted key array instead of a dense grid, so a few far-flung particles cost nothing: spray can
// spread over a domain far larger than the fluid.
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "sim/core/vec.h"

namespace spume {

class SparseBins {
 public:
  static constexpr int kBits = 21;  // bits per axis in a key: 2M cells per axis
  static constexpr int kMaxCoord = (1 << kBits) - 1;
  static constexpr int64_t kMissing = -1;

  // Key order is z, then y, then x (x fastest), so cell order is deterministic and spatially coherent.
  static uint64_t pack(int x, int y, int z) {
    return (uint64_t(z) << (2 * kBits)) | (uint64_t(y) << kBits) | uint64_t(x);
  }
  static std::array<int, 3> unpack(uint64_t key) {
    const uint64_t m = kMaxCoord;
    return {int(key & m), int((key >> kBits) & m), int((key >> (2 * kBits)) & m)};
  }

  // Bins `points` (all must lie in [origin, origin + 2^21 cell) on every axis; throws Error otherwise).
  // Within a cell, points keep ascending input order. Deterministic for any thread count.
  void build(std::span<const Vec3f> points, const Vec3f& origin, float cell);

  const Vec3f& origin() const { return origin_; }
  float cell() const { return cell_; }

  size_t cell_count() const { return keys_.size(); }
  uint64_t key(size_t c) const { return keys_[c]; }
  std::span<const uint64_t> keys() const { return keys_; }
  // Index of the occupied cell with this key, or kMissing (binary search).
  int64_t find(uint64_t key) const;
  int64_t find(int x, int y, int z) const;

  // The points of occupied cell c: their positions and their indices into the input.
  std::span<const Vec3f> points(size_t c) const {
    return {sorted_.data() + start_[c], size_t(start_[c + 1] - start_[c])};
  }
  std::span<const uint32_t> indices(size_t c) const {
    return {order_.data() + start_[c], size_t(start_[c + 1] - start_[c])};
  }

 private:
  Vec3f origin_ = Vec3f::Zero();
  float cell_ = 1.0f;
  std::vector<uint64_t> keys_;   // occupied cells, ascending
  std::vector<uint32_t> start_;  // keys_.size() + 1 offsets into sorted_/order_
  std::vector<Vec3f> sorted_;    // points in cell order
  std::vector<uint32_t> order_;  // input index of each sorted point
};

}  // namespace spume
