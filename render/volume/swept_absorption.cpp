#include "render/volume/swept_absorption.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace spume {

RaySample absorb_swept(const std::vector<SweptChord>& chords, double t_in, double t_out, const VolumeShading& shading,
                       WaterView water, SweptScratch& scratch, RayTypes* types) {
  RaySample out;
  std::vector<SweptScratch::Event>& events = scratch.events;
  events.clear();
  // One stretch a particle: its pieces' supports joined, their areas added.
  for (size_t i = 0; i < chords.size();) {
    size_t j = i + 1;
    double lo = chords[i].s_lo, hi = chords[i].s_hi, area = chords[i].area;
    for (; j < chords.size() && chords[j].particle == chords[i].particle; ++j)
      lo = std::min(lo, chords[j].s_lo), hi = std::max(hi, chords[j].s_hi), area += chords[j].area;
    const double density = std::min(1.0, area / (hi - lo));
    // The ray's ends (an opaque surface, the bounds) cut a stretch; the density stays.
    lo = std::max(lo, t_in), hi = std::min(hi, t_out);
    if (hi > lo) {
      events.push_back({lo, density, chords[i].type});
      events.push_back({hi, -density, chords[i].type});
    }
    i = j;
  }
  if (events.empty()) return out;
  std::sort(events.begin(), events.end(), [](const SweptScratch::Event& a, const SweptScratch::Event& b) {
    return std::tie(a.s, a.density, a.type) < std::tie(b.s, b.density, b.type);
  });
  std::array<double, kDiffuseTypeCount> length{}, density{};
  std::array<Vec3d, kDiffuseTypeCount> weight{Vec3d::Zero(), Vec3d::Zero(), Vec3d::Zero()};
  double total = 0.0, all = 0.0;
  for (size_t e = 0; e + 1 < events.size(); ++e) {
    all += events[e].density, density[events[e].type] += events[e].density;
    const double a = events[e].s, b = events[e + 1].s;
    if (!(b > a) || !(all > 1e-12)) continue;
    total += std::min(1.0, all) * (b - a);
    // The stretch's length dimmed by the water in front, the same for every type in it.
    const Vec3d dimmed = water.n ? dimmed_length(water.seg, water.n, shading.water_sigma, a - t_in, b - t_in)
                                 : Vec3d::Constant(b - a);
    for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k) {
      const double d = std::min(1.0, std::max(0.0, density[k]));
      if (!(d > 0.0)) continue;
      length[k] += d * (b - a);
      weight[k] += d * dimmed;
    }
  }
  out.transmittance = std::exp(-shading.alpha * total);
  mix_color(shading, length, weight, out, types);
  return out;
}

}  // namespace spume
