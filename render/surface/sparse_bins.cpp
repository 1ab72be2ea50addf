#include "render/surface/sparse_bins.h"

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <utility>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {

void SparseBins::build(std::span<const Vec3f> points, const Vec3f& origin, float cell) {
  origin_ = origin, cell_ = cell;
  const size_t n = points.size();
  // (key, input index) pairs are unique, so any correct sort gives the same order.
  std::vector<std::pair<uint64_t, uint32_t>> packed(n);
  std::atomic<bool> out_of_range = false;
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      float f[3];
      bool ok = true;
      for (int a = 0; a < 3; ++a) {
        f[a] = std::floor((points[i][a] - origin_[a]) / cell_);
        ok = ok && f[a] >= 0.0f && f[a] <= float(kMaxCoord);  // false for NaN too
      }
      if (!ok) out_of_range.store(true, std::memory_order_relaxed);
      packed[i] = {ok ? pack(int(f[0]), int(f[1]), int(f[2])) : 0, uint32_t(i)};
    }
  });
  if (out_of_range)
    fail("surface reconstruction: particles span more than ", kMaxCoord, " cells of ", cell,
         " m on an axis (or are not finite); remove far outliers or use larger cells");
  tbb::parallel_sort(packed.begin(), packed.end());

  keys_.clear(), start_.clear();
  sorted_.resize(n), order_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    if (i == 0 || packed[i].first != packed[i - 1].first) {
      keys_.push_back(packed[i].first);
      start_.push_back(uint32_t(i));
    }
    order_[i] = packed[i].second;
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
