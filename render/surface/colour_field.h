#pragma once
// The smoothed colour field of a particle set, sampled on a SPARSE lattice:
//   c(x) = sum_j V W(|x - x_j|, h),   V = (2r)^3,   W = 315 / (64 pi h^9) (h^2 - d^2)^3 (poly6)
// c is about 1 inside bulk fluid at spacing 2r and falls to 0 at distance h from the last particle.
// Poly6 is C2 (smooth normals) and needs no square root. The lattice (spacing `cell`) is stored in
// bricks of 8^3 points; only bricks near particles exist, and every point of a missing brick is
// farther than h from all particles (value exactly 0).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "sim/core/vec.h"
#include "render/surface/sparse_bins.h"
#include "sim/core/huge_page_array.h"

namespace spume {

class ColourField {
 public:
  static constexpr int kB = 8;  // lattice points per brick side
  static constexpr int kBrickPoints = kB * kB * kB;

  // Samples the field of `points` (m) with particle radius r, kernel support h and lattice spacing
  // `cell` (all m). Parallel; the values do not depend on the thread count.
  ColourField(std::span<const Vec3f> points, float particle_radius, float support, float cell);

  float cell() const { return cell_; }
  float support() const { return h_; }
  // Position of global lattice point g: the one formula used everywhere, so positions agree bitwise.
  float coord(int axis, int g) const { return origin_[axis] + float(g) * cell_; }

  size_t brick_count() const { return keys_.size(); }
  std::array<int, 3> brick_coords(size_t b) const { return SparseBins::unpack(keys_[b]); }
  int64_t find_brick(int x, int y, int z) const;
  // Values of brick b, x fastest then y then z; its min and max.
  std::span<const float> values(size_t b) const { return {values_.data() + b * kBrickPoints, size_t(kBrickPoints)}; }
  float min_value(size_t b) const { return min_[b]; }
  float max_value(size_t b) const { return max_[b]; }

  // Particles that can reach (within h) a point of brick b's lattice box grown by `margin` (m), in a
  // fixed order.
  void gather(size_t b, float margin, std::vector<Vec3f>& out) const;

 private:
  // Bricks are sampled kGroup^3 at a time into one dense lattice of kG^3 points (128 KiB): a
  // kernel's box (9 points a side at the default cell) nearly always spans two bricks per axis, so
  // cut per brick it made 8 short pieces; per group about 2 (1.25 a side), and a group gathers its
  // particles once. Groups of 2 bricks a side took 385 ms against 312 on the lighthouse's 643k.
  static constexpr int kGroup = 4;
  static constexpr int kG = kGroup * kB;
  // Particles within h (grown by `margin`) of the lattice box of the `bricks`^3 bricks from `first`.
  void gather(const std::array<int, 3>& first, int bricks, float margin, std::vector<Vec3f>& out) const;
  // Adds every candidate's kernel to the kG^3 lattice points of the group whose first brick is `first`.
  void splat(const std::array<int, 3>& first, std::span<const Vec3f> candidates, float* dense) const;

  float h_, cell_, scale_;
  int reach_;  // bricks around a brick that can hold particles reaching it (+ one cell)
  Vec3f origin_;
  SparseBins particles_;        // particles binned by brick
  std::vector<uint64_t> keys_;  // bricks, ascending
  HugePageArray<float> values_;  // every point written once, so not zero-filled first
  std::vector<float> min_, max_;
};

}  // namespace spume
