#include "render/surface/colour_field.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/core/parallel.h"

namespace spume {

ColourField::ColourField(std::span<const Vec3f> points, float particle_radius, float support, float cell)
    : h_(support), cell_(cell) {
  const float volume = 8.0f * particle_radius * particle_radius * particle_radius;  // (2r)^3, m^3
  scale_ = volume * 315.0f / (64.0f * std::numbers::pi_v<float> * support * support * support);
  const float brick = kB * cell;
  // A lattice cell with a corner within h of a particle has its lower corner within h + cell of it on
  // every axis, so bricks up to `reach_` away hold every particle that matters to a brick, and the
  // bricks `reach_` around occupied ones hold every cell the surface passes through.
  reach_ = int(std::ceil((support + cell) / brick));
  if (points.empty()) {
    origin_ = Vec3f::Zero();
    return;
  }
  Aabb box;
  for (const Vec3f& p : points) box.extend(p);
  origin_ = box.min - Vec3f::Constant(float(reach_ + 1) * brick);
  particles_.build(points, origin_, brick);

  // Active bricks: the occupied ones dilated by reach_.
  const size_t occupied = particles_.cell_count();
  const int side = 2 * reach_ + 1;
  keys_.resize(occupied * size_t(side * side * side));
  parallel_for(occupied, 256, [&](size_t b, size_t e) {
    for (size_t o = b; o < e; ++o) {
      const auto [x, y, z] = SparseBins::unpack(particles_.key(o));
      size_t k = o * size_t(side * side * side);
      for (int dz = -reach_; dz <= reach_; ++dz)
        for (int dy = -reach_; dy <= reach_; ++dy)
          for (int dx = -reach_; dx <= reach_; ++dx) keys_[k++] = SparseBins::pack(x + dx, y + dy, z + dz);
    }
  });
  tbb::parallel_sort(keys_.begin(), keys_.end());
  keys_.erase(std::unique(keys_.begin(), keys_.end()), keys_.end());

  // Active bricks by group: (group key, brick) pairs, sorted, so each group's bricks are side by side.
  std::vector<std::pair<uint64_t, uint32_t>> grouped(keys_.size());
  parallel_for(keys_.size(), 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const auto [x, y, z] = SparseBins::unpack(keys_[i]);
      grouped[i] = {SparseBins::pack(x / kGroup, y / kGroup, z / kGroup), uint32_t(i)};
    }
  });
  tbb::parallel_sort(grouped.begin(), grouped.end());
  std::vector<size_t> group_start;
  for (size_t i = 0; i < grouped.size(); ++i)
    if (i == 0 || grouped[i].first != grouped[i - 1].first) group_start.push_back(i);
  group_start.push_back(grouped.size());

  values_.allocate(keys_.size() * kBrickPoints);
  min_.resize(keys_.size()), max_.resize(keys_.size());
  parallel_for(group_start.size() - 1, 1, [&](size_t g0, size_t g1) {
    std::vector<Vec3f> candidates;
    std::vector<float> dense(size_t(kG * kG * kG));
    for (size_t g = g0; g < g1; ++g) {
      const auto group = SparseBins::unpack(grouped[group_start[g]].first);
      const std::array<int, 3> first{group[0] * kGroup, group[1] * kGroup, group[2] * kGroup};
      std::fill(dense.begin(), dense.end(), 0.0f);
      gather(first, kGroup, 0.0f, candidates);
      splat(first, candidates, dense.data());
      for (size_t i = group_start[g]; i < group_start[g + 1]; ++i) {
        const size_t b = grouped[i].second;
        const auto c = brick_coords(b);
        const float* corner = dense.data() + (((c[2] - first[2]) * kG + c[1] - first[1]) * kG + c[0] - first[0]) * kB;
        float* v = values_.data() + b * kBrickPoints;
        for (int k = 0; k < kB; ++k)
          for (int j = 0; j < kB; ++j) {
            const float* row = corner + (k * kG + j) * kG;
            for (int x = 0; x < kB; ++x) *v++ = row[x] * scale_;
          }
        const auto [lo, hi] = std::minmax_element(v - kBrickPoints, v);
        min_[b] = *lo, max_[b] = *hi;
      }
    }
  });
}

int64_t ColourField::find_brick(int x, int y, int z) const {
  if (x < 0 || y < 0 || z < 0 || x > SparseBins::kMaxCoord || y > SparseBins::kMaxCoord || z > SparseBins::kMaxCoord)
    return SparseBins::kMissing;
  const uint64_t key = SparseBins::pack(x, y, z);
  const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
  return (it != keys_.end() && *it == key) ? int64_t(it - keys_.begin()) : SparseBins::kMissing;
}

void ColourField::gather(size_t b, float margin, std::vector<Vec3f>& out) const {
  gather(brick_coords(b), 1, margin, out);
}

void ColourField::gather(const std::array<int, 3>& first, int bricks, float margin, std::vector<Vec3f>& out) const {
  out.clear();
  Vec3f lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = coord(a, first[a] * kB) - h_ - margin;
    hi[a] = coord(a, (first[a] + bricks) * kB - 1) + h_ + margin;
  }
  // Bins ascending in z, then y, then x, and each bin's particles in input order: any two particles
  // keep the same relative order whatever box is gathered, so a lattice point's sum does too.
  for (int z = first[2] - reach_; z < first[2] + bricks + reach_; ++z)
    for (int y = first[1] - reach_; y < first[1] + bricks + reach_; ++y)
      for (int x = first[0] - reach_; x < first[0] + bricks + reach_; ++x) {
        const int64_t o = particles_.find(x, y, z);
        if (o == SparseBins::kMissing) continue;
        for (const Vec3f& p : particles_.points(size_t(o)))
          if ((p.array() > lo.array()).all() && (p.array() < hi.array()).all()) out.push_back(p);
      }
}

// Each particle adds its kernel to the group's points within h. One task owns a group and adds its
// particles in gather order, so every value is the same sum in the same order on any thread count.
void ColourField::splat(const std::array<int, 3>& first, std::span<const Vec3f> candidates, float* dense) const {
  float px[kG], py[kG], pz[kG];
  for (int i = 0; i < kG; ++i) {
    px[i] = coord(0, first[0] * kB + i);
    py[i] = coord(1, first[1] * kB + i);
    pz[i] = coord(2, first[2] * kB + i);
  }
  // Work in units of h: q = 1 - |x - p|^2 / h^2, over the points of the particle's bounding box
  // (clamped at 0 outside its sphere).
  const float inv_h = 1.0f / h_, inv_cell = 1.0f / cell_;
  float sx[kG];
  for (int i = 0; i < kG; ++i) sx[i] = px[i] * inv_h;
  auto range = [&](float p, float first_coord, int& lo, int& hi) {
    lo = std::max(0, int(std::ceil((p - h_ - first_coord) * inv_cell)));
    hi = std::min(kG - 1, int(std::floor((p + h_ - first_coord) * inv_cell)));
  };
  for (const Vec3f& p : candidates) {
    int i0, i1, j0, j1, k0, k1;
    range(p.x(), px[0], i0, i1);
    range(p.y(), py[0], j0, j1);
    range(p.z(), pz[0], k0, k1);
    float dx2[kG];
    for (int i = i0; i <= i1; ++i) {
      const float dx = sx[i] - p.x() * inv_h;
      dx2[i] = dx * dx;
    }
    for (int k = k0; k <= k1; ++k) {
      const float dz = (pz[k] - p.z()) * inv_h, dz2 = dz * dz;
      for (int j = j0; j <= j1; ++j) {
        const float dy = (py[j] - p.y()) * inv_h, a = 1.0f - (dy * dy + dz2);
        if (a <= 0.0f) continue;
        float* row = dense + (k * kG + j) * kG;
        for (int i = i0; i <= i1; ++i) {
          const float q = std::max(a - dx2[i], 0.0f);
          row[i] += q * q * q;
        }
      }
    }
  }
}

}  // namespace spume
