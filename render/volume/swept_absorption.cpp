#include "render/volume/swept_absorption.h"

#include <algorithm>
#include <cmath>

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
  // By position; at one position ends (negative) before starts, so touching stretches do not overlap.
  // (Equal events are interchangeable: the sums between positions do not depend on their order.)
  std::sort(events.begin(), events.end(), [](const SweptScratch::Event& a, const SweptScratch::Event& b) {
    return a.s < b.s || (a.s == b.s && a.density < b.density);
  });
  std::array<double, kDiffuseTypeCount> length{}, density{}, run_length{};
  std::array<Vec3d, kDiffuseTypeCount> weight{Vec3d::Zero(), Vec3d::Zero(), Vec3d::Zero()};
  double total = 0.0, all = 0.0, run_start = 0.0;
  bool in_run = false;
  // The water dims a run of material (a stretch with no gap) by its mean over the run: one integral a
  // run, where the material's density changes at every event.
  auto end_run = [&](double run_end) {
    const double span = run_end - run_start;
    const Vec3d dim = water.n && span > 0.0
                          ? Vec3d(dimmed_length(water.seg, water.n, shading.water_sigma, run_start - t_in, run_end - t_in) / span)
                          : Vec3d::Ones();
    for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k) weight[k] += run_length[k] * dim, run_length[k] = 0.0;
    in_run = false;
  };
  for (size_t e = 0; e + 1 < events.size(); ++e) {
    all += events[e].density, density[events[e].type] += events[e].density;
    const double a = events[e].s, b = events[e + 1].s;
    if (!(all > 1e-12)) {
      if (in_run) end_run(a);
      continue;
    }
    if (!in_run) in_run = true, run_start = a;
    if (!(b > a)) continue;
    total += std::min(1.0, all) * (b - a);
    for (size_t k = 0; k < size_t(kDiffuseTypeCount); ++k) {
      const double d = std::min(1.0, std::max(0.0, density[k]));
      length[k] += d * (b - a), run_length[k] += d * (b - a);
    }
  }
  if (in_run) end_run(events.back().s);
  out.transmittance = std::exp(-shading.alpha * total);
  mix_color(shading, length, weight, out, types);
  return out;
}

}  // namespace spume
