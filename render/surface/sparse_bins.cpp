#include "render/surface/sparse_bins.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <utility>

#include "sim/core/error.h"
#include "sim/core/parallel.h"
#include "sim/core/radix_sort.h"

namespace spume {

void SparseBins::build(std::span<const Vec3f> points, const Vec3f& origin, float cell) {
  origin_ = origin, cell_ = cell;
  const size_t n = points.size();
  // Each point's cell, and the largest cell coordinate per axis (exact in any order).
  std::vector<uint64_t> packed(n);
  const size_t chunks = std::clamp<size_t>(n / 4096, 1, 256);
  std::vector<std::array<int, 3>> most(chunks, {0, 0, 0});
  std::atomic<bool> out_of_range = false;
  parallel_for(chunks, 1, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c)
      for (size_t i = c * n / chunks; i < (c + 1) * n / chunks; ++i) {
        float f[3];
        bool ok = true;
        for (int a = 0; a < 3; ++a) {
          f[a] = std::floor((points[i][a] - origin_[a]) / cell_);
          ok = ok && f[a] >= 0.0f && f[a] <= float(kMaxCoord);  // false for NaN too
        }
        if (!ok) {
          out_of_range.store(true, std::memory_order_relaxed);
          continue;
        }
        for (int a = 0; a < 3; ++a) most[c][size_t(a)] = std::max(most[c][size_t(a)], int(f[a]));
        packed[i] = pack(int(f[0]), int(f[1]), int(f[2]));
      }
  });
  if (out_of_range)
    fail("surface reconstruction: particles span more than ", kMaxCoord, " cells of ", cell,
         " m on an axis (or are not finite); remove far outliers or use larger cells");
  std::array<uint64_t, 3> extent{1, 1, 1};
  for (const auto& m : most)
    for (int a = 0; a < 3; ++a) extent[size_t(a)] = std::max(extent[size_t(a)], uint64_t(m[size_t(a)]) + 1);

  // Into cell order, points of a cell in input order. Over a box of at most 2^32 cells, the cells'
  // dense keys (x fastest, as pack) have the same order as their packed keys, and a stable radix sort
  // of them is linear; beyond that, a comparison sort of (key, index) pairs gives the same order.
  order_.resize(n);
  if (extent[0] * extent[1] * extent[2] <= (uint64_t(1) << 32)) {
    std::vector<uint32_t> dense(n);
    parallel_for(n, 8192, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) {
        const auto [x, y, z] = unpack(packed[i]);
        dense[i] = uint32_t(uint64_t(x) + extent[0] * (uint64_t(y) + extent[1] * uint64_t(z)));
      }
    });
    RadixSorter sorter;
    sorter.sort(dense, int(std::bit_width(extent[0] * extent[1] * extent[2] - 1)));
    order_.swap(sorter.order());
  } else {
    std::vector<std::pair<uint64_t, uint32_t>> pairs(n);
    parallel_for(n, 8192, [&](size_t b, size_t e) {
      for (size_t i = b; i < e; ++i) pairs[i] = {packed[i], uint32_t(i)};
    });
    tbb::parallel_sort(pairs.begin(), pairs.end());
    for (size_t i = 0; i < n; ++i) order_[i] = pairs[i].second;
  }

  keys_.clear(), start_.clear();
  sorted_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const uint64_t key = packed[order_[i]];
    if (i == 0 || key != keys_.back()) {
      keys_.push_back(key);
      start_.push_back(uint32_t(i));
    }
  }
  start_.push_back(uint32_t(n));
  parallel_for(n, 8192, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) sorted_[i] = points[order_[i]];
  });
}

int64_t SparseBins::find(uint64_t key) const {
  const auto it = std::lower_bound(keys_.begin(), keys_.end(), key);
  return (it != keys_.end() && *it == key) ? int64_t(it - keys_.begin()) : kMissing;
}

int64_t SparseBins::find(int x, int y, int z) const {
  if (x < 0 || y < 0 || z < 0 || x > kMaxCoord || y > kMaxCoord || z > kMaxCoord) return kMissing;
  return find(pack(x, y, z));
}

}  // namespace spume
