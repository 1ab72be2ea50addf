#include "sim/core/frame_order.h"

#include <algorithm>
#include <vector>

#include "sim/core/error.h"

namespace spume {
namespace {

// Frames this small say nothing reliable about their order; they are paired by index as given.
constexpr size_t kOrderCheckMinParticles = 8;
// Index pairs checked for the order: a fixed stride through the frame, so the test costs the same on
// every frame and does not depend on the thread count.
constexpr size_t kOrderCheckSamples = 4096;
// Kept order: the predicted positions miss by under this share of the distance between unrelated
// particles (a reordered frame misses by about that distance itself).
constexpr float kOrderCheckRatio = 0.25f;

float median_of(std::vector<float>& values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace

std::string index_order_mismatch(const FluidFrame& current, const FluidFrame& next, double frame_dt) {
  const size_t n = current.size();
  if (n < kOrderCheckMinParticles) return "";
  const size_t stride = std::max<size_t>(1, n / kOrderCheckSamples);
  std::vector<float> miss, unrelated;
  for (size_t i = 0; i < n; i += stride) {
    const Vec3f predicted =
        current.positions[i] + (current.has_velocities() ? Vec3f(float(frame_dt) * current.velocities[i]) : Vec3f::Zero());
    miss.push_back((next.positions[i] - predicted).norm());
    unrelated.push_back((next.positions[i] - next.positions[(i + n / 2) % n]).norm());
  }
  const float m = median_of(miss), u = median_of(unrelated);
  if (m <= kOrderCheckRatio * u) return "";
  return str("the index order changes: particle i lands ", m, " m (median) from where its ",
             current.has_velocities() ? "stored velocity puts it" : "position was",
             ", about the ", u, " m between unrelated particles");
}

}  // namespace spume
