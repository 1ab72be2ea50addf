#include "sim/core/frames.h"

#include <algorithm>
#include <atomic>
#include <cstring>

#include "sim/core/error.h"
#include "sim/core/huge_pages.h"
#include "sim/core/parallel.h"

namespace spume {
namespace {

// Whether any of the n floats at x is infinite or NaN (all exponent bits set): one test a value and no
// branch, so the loop vectorizes.
uint32_t any_non_finite(const float* x, size_t n) {
  uint32_t found = 0;
  for (size_t k = 0; k < n; ++k) {
    uint32_t bits;
    std::memcpy(&bits, x + k, sizeof bits);
    found |= uint32_t((bits & 0x7f800000u) == 0x7f800000u);
  }
  return found;
}

}  // namespace

const char* to_string(DiffuseType t) {
  switch (t) {
    case DiffuseType::Spray: return "spray";
    case DiffuseType::Foam: return "foam";
    case DiffuseType::Bubble: return "bubble";
  }
  return "unknown";
}

void FluidFrame::validate(const std::string& where) const {
  const size_t n = positions.size();
  if (!velocities.empty() && velocities.size() != n)
    fail(where, ": ", velocities.size(), " velocities for ", n, " positions");
  if (!ids.empty() && ids.size() != n) fail(where, ": ", ids.size(), " ids for ", n, " positions");
  if (!masses.empty() && masses.size() != n) fail(where, ": ", masses.size(), " masses for ", n, " positions");
  for (size_t i = 0; i < n; ++i) {
    if (!finite(positions[i]))
      fail(where, ": particle ", i, " (id ", id(i), ") has a non-finite position (", positions[i].transpose(),
           "); positions must be finite numbers");
    if (!velocities.empty() && !finite(velocities[i]))
      fail(where, ": particle ", i, " (id ", id(i), ") has a non-finite velocity (", velocities[i].transpose(), ")");
    // A mass of 0 or less (Houdini's -1: not set) is kept as the file holds it: `info` shows it, and the
    // diffuse simulation weighs such a particle with the uniform mass (core/unusable_masses.h).
    if (!masses.empty() && !std::isfinite(masses[i]))
      fail(where, ": particle ", i, " (id ", id(i), ") has mass ", masses[i], "; masses must be finite numbers");
  }
  if (!ids.empty()) {
    std::vector<uint32_t> sorted(ids);
    std::sort(sorted.begin(), sorted.end());
    const auto dup = std::adjacent_find(sorted.begin(), sorted.end());
    if (dup != sorted.end()) fail(where, ": particle id ", *dup, " occurs more than once; ids must be unique");
  }
}

void DiffuseFrame::resize(size_t n) {
  resize_in_huge_pages(ids, n);
  resize_in_huge_pages(positions, n);
  resize_in_huge_pages(velocities, n);
  resize_in_huge_pages(lifetimes, n);
  resize_in_huge_pages(types, n);
}

void DiffuseFrame::reserve(size_t n) {
  reserve_in_huge_pages(ids, n);
  reserve_in_huge_pages(positions, n);
  reserve_in_huge_pages(velocities, n);
  reserve_in_huge_pages(lifetimes, n);
  reserve_in_huge_pages(types, n);
}

std::array<size_t, kDiffuseTypeCount> DiffuseFrame::count_by_type() const { return count_types(types); }

std::array<size_t, kDiffuseTypeCount> DiffuseView::count_by_type() const { return count_types(types); }

std::array<size_t, kDiffuseTypeCount> count_types(std::span<const DiffuseType> types) {
  // In parallel over fixed chunks (every frame is counted by the simulator, its cache and the
  // renderer); integer sums, so the split cannot change them.
  const size_t n = types.size(), chunks = std::max<size_t>(1, n >> 16);
  std::vector<std::array<size_t, kDiffuseTypeCount>> part(chunks);
  parallel_for(chunks, 1, [&](size_t cb, size_t ce) {
    for (size_t c = cb; c < ce; ++c) {
      // Comparisons summed, not a counter picked per particle (each increment then waited for the one
      // before to the same counter): vectorised, 15M types take 2.7 ms on one core instead of 11.1.
      // A byte that is no type matches none of them.
      static_assert(kDiffuseTypeCount == 3);
      uint32_t spray = 0, foam = 0, bubble = 0;  // a chunk holds fewer than 2^17 particles
      for (size_t i = c * n / chunks, end = (c + 1) * n / chunks; i < end; ++i) {
        const uint8_t t = uint8_t(types[i]);
        spray += t == 0, foam += t == 1, bubble += t == 2;
      }
      part[c] = {spray, foam, bubble};
    }
  });
  std::array<size_t, kDiffuseTypeCount> counts{};
  for (const auto& p : part)
    for (int t = 0; t < kDiffuseTypeCount; ++t) counts[size_t(t)] += p[size_t(t)];
  return counts;
}

void DiffuseFrame::validate(const std::string& where) const {
  const size_t n = positions.size();
  if (ids.size() != n || velocities.size() != n || lifetimes.size() != n || types.size() != n)
    fail(where, ": diffuse arrays disagree in length (positions ", n, ", ids ", ids.size(), ", velocities ",
         velocities.size(), ", lifetimes ", lifetimes.size(), ", types ", types.size(), ")");
  auto bad = [&](size_t i) {
    return !finite(positions[i]) || !finite(velocities[i]) || !std::isfinite(lifetimes[i]) ||
           uint8_t(types[i]) >= kDiffuseTypeCount;
  };
  // Blocks checked without a branch per value (vectorized), then the block holding a bad particle one
  // particle at a time.
  auto block_is_bad = [&](size_t b, size_t e) {
    const size_t m = e - b;
    uint32_t found = any_non_finite(positions[b].data(), 3 * m) | any_non_finite(velocities[b].data(), 3 * m) |
                     any_non_finite(&lifetimes[b], m);
    for (size_t i = b; i < e; ++i) found |= uint32_t(uint8_t(types[i]) >= kDiffuseTypeCount);
    return found != 0;
  };
  // In parallel (every cache write checks its frame: 50 ms at 14M on one core), reporting the first
  // bad particle whatever the split: each chunk offers its first, the smallest wins.
  constexpr size_t kBlock = 4096;
  std::atomic<size_t> first{n};
  parallel_for(n, 1 << 16, [&](size_t b, size_t e) {
    for (size_t block = b; block < e && block < first.load(std::memory_order_relaxed); block += kBlock) {
      const size_t block_end = std::min(e, block + kBlock);
      if (!block_is_bad(block, block_end)) continue;
      for (size_t i = block; i < block_end; ++i)
        if (bad(i)) {
          size_t seen = first.load();
          while (i < seen && !first.compare_exchange_weak(seen, i)) {
          }
          return;
        }
    }
  });
  const size_t i = first.load();
  if (i == n) return;
  if (uint8_t(types[i]) >= kDiffuseTypeCount && finite(positions[i]) && finite(velocities[i]) && std::isfinite(lifetimes[i]))
    fail(where, ": diffuse particle ", i, " has type ", int(types[i]), "; allowed 0 spray, 1 foam, 2 bubble");
  fail(where, ": diffuse particle ", i, " (id ", ids[i], ") has a non-finite value");
}

}  // namespace spume
