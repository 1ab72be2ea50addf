#pragma once
// FLIP particles as what they are (MODEL.md §9.2). The paper's model assumes SPH particles: an even
// spacing of 2r at rest and velocities that are smooth from one particle to the next. A FLIP cache
// has neither: its particles carry particle-scale velocity noise (which Eq. 2 sums as trapped air
// everywhere) and solvers reseed them, so the same water holds more or fewer particles from frame to
// frame (a raw neighbour count then moves water into bubbles or spray).
#include <vector>

#include "sim/diffuse/fluid_state.h"
#include "sim/diffuse/params.h"
#include "sim/grid/neighbour_grid.h"

namespace spume {

// A full neighbourhood's count is taken at this quantile of the particles' own counts within h: the
// interior, not the surface layers, whatever the share of the surface.
inline constexpr double kFullCountQuantile = 0.9;
// The measured density is used within [1/8, 8] times the nominal one (2r spacing): above, clamped;
// below, there is no interior to measure and the nominal density stands.
inline constexpr float kMaxDensityRatio = 8.0f;
// Kernel-averaged velocities over this many h: about two FLIP grid cells at the usual two particles per
// cell and axis (h = 4r = one cell), the reach of the grid's own interpolation both ways.
inline constexpr float kVelocitySmoothing = 2.0f;

struct FlipMeasure {
  float full_count = 0.0f;     // fluid particles within h of an interior particle, this frame
  float nominal_count = 0.0f;  // the same for particles at spacing 2r: 4/3 pi h^3 / (2r)^3
  float density_ratio = 1.0f;  // full / nominal, at most 8; 1 when below 1/8 (no interior to measure)
};

class FlipFluid {
 public:
  // Replaces state.velocities by their poly6 average over kVelocitySmoothing h (each particle with
  // weight 1 for itself) and measures the frame's particle density from the particles' own counts.
  FlipMeasure prepare(FluidStepState& state, float particle_radius, float h);

 private:
  NeighbourGrid grid_;
  std::vector<Vec3f> sorted_velocity_, smoothed_;
  std::vector<float> counts_;
};

// The parameters that count particles, carried to a density `ratio` times the nominal one: the
// classification limits and hysteresis and the trapped-air band (sums over neighbours) times the
// ratio, the crest band (a sum over surface neighbours) times ratio^(2/3), the emission rates (per fluid particle) divided by it, so the same water forms
// and classifies alike whatever its particle count.
DiffuseParams at_density(const DiffuseParams& params, float ratio);

}  // namespace spume
