#include "sim/diffuse/fluid_state.h"

#include <algorithm>
#include <numeric>

#include "sim/core/error.h"
#include "sim/core/frame_order.h"
#include "sim/core/huge_pages.h"
#include "sim/core/parallel.h"
#include "sim/core/unusable_masses.h"

namespace spume {
FramePair pair_frames(const FluidFrame& current, const FluidFrame* next, double frame_dt) {
  FramePair pair;
  pair.current = &current;
  pair.next = next;
  pair.frame_dt = frame_dt;
  const size_t n = current.size();
  pair.next_index.assign(n, -1);
  if (!next) return pair;
  if (!current.has_ids() || !next->has_ids()) {
    // Without ids on both sides an index says nothing by itself: pair by index only where the counts
    // agree and the order is kept.
    if (current.size() != next->size())
      pair.unpaired_because = str("the particle count changes (", current.size(), " -> ", next->size(), ")");
    else
      pair.unpaired_because = index_order_mismatch(current, *next, frame_dt);
    if (pair.unpaired_because.empty()) std::iota(pair.next_index.begin(), pair.next_index.end(), 0);
    return pair;
  }
  // Fast path: same ids in the same order.
  if (current.ids == next->ids) {
    std::iota(pair.next_index.begin(), pair.next_index.end(), 0);
    return pair;
  }
  // General case: join on id through the next frame's ids sorted once.
  std::vector<uint32_t> by_id(next->size());
  std::iota(by_id.begin(), by_id.end(), 0u);
  std::sort(by_id.begin(), by_id.end(), [&](uint32_t a, uint32_t b) { return next->id(a) < next->id(b); });
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const uint32_t id = current.id(i);
      auto it = std::lower_bound(by_id.begin(), by_id.end(), id,
                                 [&](uint32_t idx, uint32_t value) { return next->id(idx) < value; });
      if (it != by_id.end() && next->id(*it) == id) pair.next_index[i] = int32_t(*it);
    }
  });
  return pair;
}

void interpolate_fluid(const FramePair& pair, float s, float uniform_mass, FluidStepState& out) {
  const FluidFrame& a = *pair.current;
  const size_t n = a.size();
  resize_in_huge_pages(out.positions, n);
  resize_in_huge_pages(out.velocities, n);
  resize_in_huge_pages(out.motion, n);
  resize_in_huge_pages(out.masses, n);
  resize_in_huge_pages(out.ids, n);
  const float inv_dt = pair.frame_dt > 0.0 ? float(1.0 / pair.frame_dt) : 0.0f;
  const float dt = float(pair.frame_dt);
  parallel_for(n, 4096, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      const int32_t j = pair.next_index[i];
      const Vec3f va = a.has_velocities() ? a.velocities[i] : Vec3f::Zero();
      if (j >= 0) {
        const FluidFrame& c = *pair.next;
        const Vec3f difference = (c.positions[j] - a.positions[i]) * inv_dt;
        out.positions[i] = a.positions[i] + s * (c.positions[j] - a.positions[i]);
        out.motion[i] = difference;
        out.velocities[i] = a.has_velocities() && c.has_velocities() ? Vec3f(va + s * (c.velocities[j] - va))
                                                                      : difference;
      } else {
        out.positions[i] = a.positions[i] + (s * dt) * va;
        out.motion[i] = va;
        out.velocities[i] = va;
      }
      out.masses[i] = a.masses.empty() || !usable_mass(a.masses[i]) ? uniform_mass : a.masses[i];
      out.ids[i] = a.id(i);
    }
  });
}

}  // namespace spume
