#pragma once
// From the moving spheres one eye ray meets during the shutter to its transmittance and colour
// (motion blur, MODEL.md §13). Each particle (its path's pieces together: they never share a time)
// is a stretch [s_lo, s_hi] of the ray holding its time-averaged chord (swept_sphere.h) spread evenly:
// a density d = area / (s_hi - s_lo) <= 1. Where stretches overlap, densities add up to at most 1, so
// that spheres at rest (d = 1 over their chords) give Eq. 9's exact union of chords, and a particle
// alone keeps its whole optical depth, alpha * area, wherever its motion spreads it.
// L = exp(-alpha * int min(1, sum d) ds); colours and water dimming as absorption.h, per type from
// min(1, sum of that type's d).
#include <vector>

#include "render/volume/absorption.h"
#include "render/volume/swept_sphere.h"

namespace spume {

struct SweptScratch {
  struct Event {
    double s;
    double density;  // + where a stretch starts, - where it ends
    uint32_t type;
  };
  std::vector<Event> events;
};

// `chords` of one ray, a particle's pieces next to each other, whose material lies in [t_in, t_out]
// (m along the ray); `water` relative to t_in, as TileRays gives it.
RaySample absorb_swept(const std::vector<SweptChord>& chords, double t_in, double t_out, const VolumeShading& shading,
                       WaterView water, SweptScratch& scratch, RayTypes* types = nullptr);

}  // namespace spume
