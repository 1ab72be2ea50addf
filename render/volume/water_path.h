#pragma once
// The stretches of an eye ray that lie in water, from its crossings of the water surface, and the
// dimming exp(-sigma_w * w(t)) of what is seen at distance t after travelling w(t) in water.
#include <vector>

#include "sim/core/vec.h"

namespace spume {

struct WaterCrossing {
  double t;       // m along the ray, same reference as the intervals
  bool entering;  // the ray goes from outside to inside the water (dot(outward normal, d) < 0)
};

struct WaterSegment {
  double t0, t1;  // m; the ray is in water on [t0, t1]; t1 may be +inf
};

// Crossings closer than this (relative to their distance from the ray origin, plus the absolute part)
// are taken as one: Embree's float hits on a grazed surface can be 30 float roundings (2e-6 m at 4 m)
// out, enough to swap the entry and the exit of a sliver of water (seen at the lighthouse).
constexpr double kMergeRelative = 1e-5, kMergeAbsolute = 1e-7;  // m/m, m

// Crossings in any order; reordered and merged in place. Crossings within kMerge* of each other are
// one event with their net sense (none when they cancel), so a crossing reported by two triangles (a
// ray through a shared edge) counts once and a sliver of water thinner than the rounding is dropped.
// The state before the first event is "outside" unless that event leaves the water (camera under
// water: its segment starts at origin_t, the ray origin in the crossings' reference). Further events
// of the sense already reached are ignored.
void water_segments(std::vector<WaterCrossing>& crossings, double origin_t, std::vector<WaterSegment>& out);

// Distance travelled in water from the ray origin to t. Segments sorted and disjoint.
double water_distance(const WaterSegment* seg, size_t n, double t);

// Integral of exp(-sigma * w(t)) dt over [a, b], per channel (sigma in 1/m): the length [a, b]
// contributes to the colour after dimming. Equals b - a when n == 0.
Vec3d dimmed_length(const WaterSegment* seg, size_t n, const Vec3d& sigma, double a, double b);

}  // namespace spume
