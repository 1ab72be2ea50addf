#include "sim/geometry/solid_clearance.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace spume {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr size_t kClearanceMaxRow = size_t(1) << 16;  // cells along one axis

using Box = Eigen::AlignedBox3d;

// Empty, or flat along an axis: no ball fits in it.
bool no_room(const Box& b) { return !(b.min().array() < b.max().array()).all(); }

}  // namespace

SolidClearance::SolidClearance(const SolidSet& solids, float reach) : built_(true) {
  // The grid covers the tanks' common interior (an open top closed at its rim: spray above the rim
  // takes the exact tests), or without a tank every solid's broad box widened by the reach.
  const double far_reach = double(reach * 1.001f);  // what SolidSet::far_from adds to its boxes
  bool any_tank = false;
  Box tanks(Vec3d::Constant(-kInf), Vec3d::Constant(kInf)), others;  // others: empty
  for (size_t i = 0; i < solids.solids().size(); ++i) {
    const Solid& s = solids.solids()[i];
    if (s.kind == Solid::Kind::Tank) {
      any_tank = true;
      tanks = tanks.intersection(Box(s.min.cast<double>(), s.max.cast<double>()));
    } else {
      others.extend(Box(solids.broad_bounds(i).min.cast<double>(), solids.broad_bounds(i).max.cast<double>()));
    }
  }
  outside_clear_ = !any_tank;
  Box grid = tanks;
  if (!any_tank) {
    if (others.isEmpty()) return;  // no solid at all: every finite point is clear
    const double widen = far_reach + 1e-3 * others.sizes().maxCoeff() + 1e-6 * others.max().cwiseAbs().maxCoeff();
    grid = Box(others.min() - Vec3d::Constant(widen), others.max() + Vec3d::Constant(widen));
  }
  if (no_room(grid) || !grid.min().allFinite() || !grid.max().allFinite()) {
    outside_clear_ = false;  // nothing can be said cheaply: every point takes the exact tests
    return;
  }

  const Vec3d extent = grid.sizes();
  double cell = std::max({double(reach), std::cbrt(extent.prod() / double(kClearanceMaxCells)), 1e-6 * extent.maxCoeff()});
  std::array<size_t, 3> n{};
  for (;;) {
    for (int a = 0; a < 3; ++a) n[size_t(a)] = std::max<size_t>(1, size_t(std::ceil(extent[a] / cell)));
    if (n[0] * n[1] * n[2] <= kClearanceMaxCells && std::max({n[0], n[1], n[2]}) <= kClearanceMaxRow) break;
    cell *= 1.25;
  }
  origin_ = grid.min().cast<float>();
  per_cell_ = float(1.0 / cell);
  if (!(per_cell_ > 0.0f) || !std::isfinite(per_cell_) || !origin_.allFinite()) {
    per_cell_ = 0.0f, outside_clear_ = false;  // beyond a float's range: every point takes the exact tests
    return;
  }
  // The cell index clear() computes in floats may put a point near a cell's side into its neighbour
  // (by a float's rounding of the index, under 0.008 of a cell at kClearanceMaxRow cells, and of the
  // coordinate): the slack widens every cell by more than that.
  const double slack = 0.02 * cell + 1e-6 * std::max(grid.min().cwiseAbs().maxCoeff(), grid.max().cwiseAbs().maxCoeff());
  const Vec3d origin = origin_.cast<double>();
  const double step = 1.0 / double(per_cell_);
  auto lo = [&](int a, size_t i) { return origin[a] + double(i) * step - slack; };
  auto hi = [&](int a, size_t i) { return origin[a] + double(i + 1) * step + slack; };
  for (int a = 0; a < 3; ++a) dims_[size_t(a)] = float(n[size_t(a)]);

  // Tank walls: separable, one verdict per row of cells along each axis. Within the reach of a wall
  // (or outside it) the exact tests have work to do.
  std::array<std::vector<uint8_t>, 3> inside;
  for (int a = 0; a < 3; ++a) {
    inside[size_t(a)].assign(n[size_t(a)], 1);
    for (size_t i = 0; i < n[size_t(a)]; ++i)
      for (const Solid& s : solids.solids()) {
        if (s.kind != Solid::Kind::Tank) continue;
        const bool walled_top = !(s.open_top && a == s.up_axis);
        if (lo(a, i) - double(s.min[a]) < double(reach) || (walled_top && double(s.max[a]) - hi(a, i) < double(reach)))
          inside[size_t(a)][i] = 0;
      }
  }
  bits_.assign((n[0] * n[1] * n[2] + 63) / 64, 0);
  for (size_t k = 0; k < n[2]; ++k)
    for (size_t j = 0; j < n[1]; ++j)
      for (size_t i = 0; i < n[0]; ++i)
        if (inside[0][i] && inside[1][j] && inside[2][k]) set(i + n[0] * (j + n[1] * k), true);

  // Boxes and spheres: every cell whose widened box comes within far_from's reach of the solid's
  // broad box loses its bit.
  for (size_t s = 0; s < solids.solids().size(); ++s) {
    if (solids.solids()[s].kind == Solid::Kind::Tank) continue;
    const Aabb& b = solids.broad_bounds(s);
    std::array<size_t, 3> first{}, last{};
    bool misses = false;
    for (int a = 0; a < 3; ++a) {
      const double from = double(b.min[a]) - far_reach, to = double(b.max[a]) + far_reach;
      // Cells i with hi(i) >= from and lo(i) <= to, found generously and then tested exactly.
      const double i0 = std::floor((from - slack - origin[a]) / step) - 1.0, i1 = std::ceil((to + slack - origin[a]) / step) + 1.0;
      if (i1 < 0.0 || i0 >= double(n[size_t(a)])) misses = true;
      first[size_t(a)] = size_t(std::clamp(i0, 0.0, double(n[size_t(a)] - 1)));
      last[size_t(a)] = size_t(std::clamp(i1, 0.0, double(n[size_t(a)] - 1)));
    }
    if (misses) continue;
    auto overlaps = [&](int a, size_t i) {
      return hi(a, i) >= double(b.min[a]) - far_reach && lo(a, i) <= double(b.max[a]) + far_reach;
    };
    for (size_t k = first[2]; k <= last[2]; ++k)
      for (size_t j = first[1]; j <= last[1]; ++j)
        for (size_t i = first[0]; i <= last[0]; ++i)
          if (overlaps(0, i) && overlaps(1, j) && overlaps(2, k)) set(i + n[0] * (j + n[1] * k), false);
  }
}

void SolidClearance::set(size_t cell, bool clear) {
  const uint64_t bit = uint64_t(1) << (cell & 63);
  if (clear) bits_[cell >> 6] |= bit;
  else bits_[cell >> 6] &= ~bit;
}

size_t SolidClearance::clear_cells() const {
  size_t count = 0;
  for (uint64_t word : bits_) count += size_t(std::popcount(word));
  return count;
}

}  // namespace spume
