#include "sim/io/up_axis_measure.h"

#include <algorithm>
#include <cmath>

#include "sim/core/error.h"

namespace spume {
namespace {

constexpr double kG = 9.81;
// A fall's acceleration, within a factor 10 of g either way: a wrong fluid.fps (by up to 3x) scales it
// by its square, and what matters is that it is one axis's, not its size.
constexpr double kMinFall = kG / 10.0, kMaxFall = kG * 10.0;
constexpr double kMinAxisShare = 0.95;      // of the acceleration along its axis
constexpr float kShapeToleranceInRadii = 2.0f;
constexpr float kMaxLayerAspect = 0.5f;     // thinnest extent over each other one
constexpr float kMinLayerInRadii = 8.0f;    // 4 spacings 2 r

const char* axis_name(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

Vec3d centroid(const FluidFrame& f) {
  Vec3d sum = Vec3d::Zero();
  for (const Vec3f& p : f.positions) sum += p.cast<double>();
  return sum / double(f.size());
}

Vec3f extent(const FluidFrame& f) {
  Aabb box;
  for (const Vec3f& p : f.positions) box.extend(p);
  return box.max - box.min;
}

// The first three frames at equal intervals and of equal counts that fall freely (see the header).
bool measure_fall(const std::vector<FluidFrame>& frames, const std::vector<int>& numbers, double fps, float radius,
                  UpAxisMeasure& m) {
  for (size_t k = 0; k + 2 < frames.size(); ++k) {
    const FluidFrame &a = frames[k], &b = frames[k + 1], &c = frames[k + 2];
    const int gap = numbers[k + 1] - numbers[k];
    if (gap <= 0 || numbers[k + 2] - numbers[k + 1] != gap || a.size() < 8 || a.size() != b.size() ||
        a.size() != c.size())
      continue;
    const Vec3f ea = extent(a);
    if (!((extent(b) - ea).cwiseAbs().maxCoeff() <= kShapeToleranceInRadii * radius) ||
        !((extent(c) - ea).cwiseAbs().maxCoeff() <= kShapeToleranceInRadii * radius))
      continue;  // the shape changes: something holds or pushes the fluid
    const double dt = double(gap) / fps;
    const Vec3d acc = (centroid(c) - 2.0 * centroid(b) + centroid(a)) / (dt * dt);
    int axis = 0;
    acc.cwiseAbs().maxCoeff(&axis);
    const double size = acc.norm();
    if (!(size >= kMinFall && size <= kMaxFall) || std::fabs(acc[axis]) < kMinAxisShare * size) continue;
    m.axis = axis;
    m.sign = acc[axis] < 0.0 ? 1 : -1;
    m.by_fall = true;
    m.how = str("frames ", numbers[k], ", ", numbers[k + 1], " and ", numbers[k + 2], " keep their shape (within ",
                kShapeToleranceInRadii, " r) while their centroid accelerates at ", float(size), " m/s^2 toward ",
                m.sign > 0 ? "-" : "+", axis_name(axis), " (at fluid.fps = ", fps, "): a free fall");
    return true;
  }
  return false;
}

bool measure_layer(const FluidFrame& last, int number, float radius, UpAxisMeasure& m) {
  if (last.size() < 8) return false;
  const Vec3f e = extent(last);
  int thin = 0;
  e.minCoeff(&thin);
  const int u = (thin + 1) % 3, w = (thin + 2) % 3;
  if (!(e[thin] <= kMaxLayerAspect * std::min(e[u], e[w])) || !(e[thin] >= kMinLayerInRadii * radius)) return false;
  m.axis = thin;
  m.sign = 1;
  m.how = str("frame ", number, " is a layer ", e[thin], " m thick along ", axis_name(thin), " and ", e[u], " x ",
              e[w], " m across (", kMaxLayerAspect, " or less of each): fluid resting on a floor");
  return true;
}

}  // namespace

UpAxisMeasure measure_up_axis(const std::vector<FluidFrame>& frames, const std::vector<int>& numbers, double fps,
                              float radius) {
  UpAxisMeasure m;
  if (frames.empty() || frames.size() != numbers.size()) return m;
  if (measure_fall(frames, numbers, fps, radius, m)) return m;
  if (measure_layer(frames.back(), numbers.back(), radius, m)) return m;
  m.how = str("in frames ", numbers.front(), "-", numbers.back(), " the fluid neither fell freely along one axis nor "
              "rested as a layer thinner along one axis than along both others");
  return m;
}

}  // namespace spume
