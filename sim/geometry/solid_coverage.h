#pragma once
// How much of a particle's neighbourhood (the ball of radius h around it) lies inside the union of
// the scene's solids, and the colour-field gradient that part would add were it fluid. The
// classification and the surface test use it to count a wall as the water it replaces, only as far
// as the wall is wet (MODEL.md §8.10, §8.11): the fluid count n becomes n / (1 - fraction).
//
// Exact where the ball meets a single flat face whose contact disc lies inside the face (a wall, a
// floor, a box side); elsewhere (edges, corners, spheres, an open tank's rim, several solids) the
// ball is integrated along a fixed set of directions with the radial part exact, which measures the
// union of the solids, never a sum over their faces (that would count an edge twice).
#include "sim/core/vec.h"
#include "sim/geometry/solids.h"

namespace spume {

struct SolidCoverage {
  float fraction = 0.0f;              // V_solid / V_h, in [0, 1]
  Vec3f gradient = Vec3f::Zero();     // ∫ over solid ∩ ball of ∇_x W(x - y) dy, 1/m; points into the solid
};

// W is the cubic spline of support h used by the surface test (core/cubic_spline.h).
// `with_gradient`: false skips the gradient (classification needs only the fraction).
SolidCoverage solid_coverage(const SolidSet& solids, const Vec3f& p, float h, bool with_gradient);

// Bounds on `fraction` without integrating, from each nearby solid's enclosing half-space (hi: their
// caps summed) and the walls known to be solid throughout their half-space (lo); lo == hi exactly when
// solid_coverage would not integrate either. Where a decision is the same at both bounds (a type, the
// surface test), the integral is not needed.
struct CoverageBounds {
  float lo = 0.0f, hi = 0.0f;
};
CoverageBounds solid_coverage_bounds(const SolidSet& solids, const Vec3f& p, float h);

// Directions of the quadrature used away from single faces (exposed for tests).
constexpr int kCoverageDirections = 256;

// The neighbour count a fluid count n stands for next to solids covering `fraction` of the ball:
// n / (1 - fraction), with the free share floored at 1/10 (a particle pushed into a tank corner
// keeps 1/8 free; deeper than that the count stops growing instead of dividing by zero).
inline float wet_wall_count(float fluid_count, float fraction) {
  return fluid_count / std::max(1.0f - fraction, 0.1f);
}

}  // namespace spume
