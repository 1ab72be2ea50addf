#include "render/volume/drawn_bounds.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

namespace spume {
namespace {

constexpr size_t kLanes = 8;

// Minima and maxima are exact in any order, so lanes and chunks may be any.
struct Box {
  float lo[3][kLanes], hi[3][kLanes];
  size_t drawn = 0;
  Box() {
    for (int a = 0; a < 3; ++a) std::fill_n(lo[a], kLanes, INFINITY), std::fill_n(hi[a], kLanes, -INFINITY);
  }
};

// Particles [begin, end) into the box, 8 at a time without a branch (vectorized); returns whether one
// of them is bad (type beyond 2, or a drawn sphere's centre not finite). Built for AVX2 and baseline
// x86-64, picked at load time. At 15M spheres the branchy loop took 60-80 ms of the volume pass.
__attribute__((target_clones("avx2", "default"))) bool add_range(const Vec3f* position, const DiffuseType* type,
                                                                 const float* radius_of, size_t begin, size_t end,
                                                                 Box& box) {
  uint32_t bad = 0;
  size_t drawn = 0;
  for (size_t b = begin; b < end; b += kLanes) {
    const size_t m = std::min(kLanes, end - b);
    for (size_t l = 0; l < kLanes; ++l) {
      const size_t i = b + (l < m ? l : 0);  // past the end: the block's first particle again
      const uint8_t t = uint8_t(type[i]);
      const float r = radius_of[std::min<uint8_t>(t, kDiffuseTypeCount)];  // 0 past the types
      const bool is_drawn = r > 0.0f && l < m;
      const float x = position[i].x(), y = position[i].y(), z = position[i].z();
      const bool finite = std::abs(x) <= 3.4028235e38f && std::abs(y) <= 3.4028235e38f && std::abs(z) <= 3.4028235e38f;
      bad |= uint32_t((t >= kDiffuseTypeCount || (is_drawn && !finite)) && l < m);
      const bool use = is_drawn && finite;
      box.lo[0][l] = std::min(box.lo[0][l], use ? x - r : INFINITY), box.hi[0][l] = std::max(box.hi[0][l], use ? x + r : -INFINITY);
      box.lo[1][l] = std::min(box.lo[1][l], use ? y - r : INFINITY), box.hi[1][l] = std::max(box.hi[1][l], use ? y + r : -INFINITY);
      box.lo[2][l] = std::min(box.lo[2][l], use ? z - r : INFINITY), box.hi[2][l] = std::max(box.hi[2][l], use ? z + r : -INFINITY);
      drawn += use;
    }
  }
  box.drawn += drawn;
  return bad != 0;
}

}  // namespace

Aabb drawn_bounds(DiffuseView frame, const std::array<float, kDiffuseTypeCount>& radius, size_t& count) {
  const size_t n = frame.size(), chunks = std::clamp<size_t>(n / 65536, 1, 64);
  float radius_of[kDiffuseTypeCount + 1];
  for (int k = 0; k < kDiffuseTypeCount; ++k) radius_of[k] = radius[size_t(k)];
  radius_of[kDiffuseTypeCount] = 0.0f;
  std::vector<Box> box(chunks);
  std::vector<size_t> bad(chunks, SIZE_MAX);
  parallel_for(chunks, 1, [&](size_t c0, size_t c1) {
    for (size_t c = c0; c < c1; ++c) {
      const size_t begin = c * n / chunks, end = (c + 1) * n / chunks;
      if (begin == end || !add_range(frame.positions.data(), frame.types.data(), radius_of, begin, end, box[c])) continue;
      for (size_t i = begin; i < end && bad[c] == SIZE_MAX; ++i) {  // which one, for the message
        const size_t t = size_t(frame.types[i]);
        const Vec3f& p = frame.positions[i];
        if (t >= size_t(kDiffuseTypeCount) || (radius_of[t] > 0.0f && !(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()))))
          bad[c] = i;
      }
    }
  });
  Aabb all;
  count = 0;
  for (size_t c = 0; c < chunks; ++c) {
    if (bad[c] != SIZE_MAX)
      fail("volume pass: frame ", frame.index, " particle ", bad[c], " has a non-finite position or a type outside 0..2");
    for (int a = 0; a < 3; ++a)
      for (size_t l = 0; l < kLanes; ++l)
        all.min[a] = std::min(all.min[a], box[c].lo[a][l]), all.max[a] = std::max(all.max[a], box[c].hi[a][l]);
    count += box[c].drawn;
  }
  return all;
}

}  // namespace spume
