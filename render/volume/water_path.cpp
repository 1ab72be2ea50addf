#include "render/volume/water_path.h"

#include <algorithm>
#include <cmath>

namespace spume {

void water_segments(std::vector<WaterCrossing>& crossings, double origin_t, std::vector<WaterSegment>& out) {
  out.clear();
  if (crossings.empty()) return;
  std::sort(crossings.begin(), crossings.end(), [](const WaterCrossing& a, const WaterCrossing& b) {
    return a.t != b.t ? a.t < b.t : a.entering < b.entering;
  });
  // Crossings within each other's rounding are one event, whose sense is their net count: a crossing
  // reported by two triangles counts once, and a sliver of water thinner than the rounding, whose two
  // crossings may come out in either order, is no crossing at all.
  auto merged = [&](double a, double b) { return b - a <= kMergeRelative * std::abs(b - origin_t) + kMergeAbsolute; };
  size_t events = 0;
  for (size_t i = 0; i < crossings.size();) {
    size_t j = i + 1;
    int net = crossings[i].entering ? 1 : -1;
    for (; j < crossings.size() && merged(crossings[j - 1].t, crossings[j].t); ++j) net += crossings[j].entering ? 1 : -1;
    if (net != 0) crossings[events++] = {crossings[i].t, net > 0};
    i = j;
  }
  crossings.resize(events);
  if (crossings.empty()) return;
  bool inside = !crossings.front().entering;
  double start = origin_t;  // used when the ray begins in water
  for (const WaterCrossing& c : crossings) {
    if (c.entering && !inside) start = c.t, inside = true;
    else if (!c.entering && inside) {
      out.push_back({start, c.t});
      inside = false;
    }
  }
  if (inside) out.push_back({start, INFINITY});
}

double water_distance(const WaterSegment* seg, size_t n, double t) {
  double w = 0.0;
  for (size_t i = 0; i < n && seg[i].t0 < t; ++i) w += std::min(t, seg[i].t1) - seg[i].t0;
  return w;
}

namespace {
// Integral of exp(-s (w0 + x)) over x in [0, len]: exp(-s w0) (1 - exp(-s len)) / s, and
// exp(-s w0) len as s -> 0. expm1 keeps it accurate for small s len.
double wet_integral(double s, double w0, double len) {
  const double fade = std::exp(-s * w0);
  return s > 0.0 ? fade * (-std::expm1(-s * len) / s) : fade * len;
}
}  // namespace

Vec3d dimmed_length(const WaterSegment* seg, size_t n, const Vec3d& sigma, double a, double b) {
  if (n == 0 || b <= a) return Vec3d::Constant(std::max(0.0, b - a));
  Vec3d sum = Vec3d::Zero();
  double t = a, w = water_distance(seg, n, a);
  auto dry = [&](double t_end) {  // out of water: constant dimming exp(-sigma w)
    for (int c = 0; c < 3; ++c) sum[c] += std::exp(-sigma[c] * w) * (t_end - t);
    t = t_end;
  };
  for (size_t i = 0; i < n && t < b; ++i) {
    if (seg[i].t1 <= t) continue;
    if (seg[i].t0 >= b) break;
    if (seg[i].t0 > t) dry(seg[i].t0);
    const double end = std::min(seg[i].t1, b), len = end - t;
    for (int c = 0; c < 3; ++c) sum[c] += wet_integral(sigma[c], w, len);
    w += len;
    t = end;
  }
  if (t < b) dry(b);
  return sum;
}

}  // namespace spume
