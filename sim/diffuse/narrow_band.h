#pragma once
// Narrow-band caches (MODEL.md §9.1): FLIP solvers (Blender's Mantaflow, Houdini) often keep particles
// only in a band a few cells thick under the liquid's surface, the interior being carried by their
// grids. A bubble inside would count no fluid neighbours and become spray. This decides whether a frame
// is such a band (one test, used by `spume info` and by the run alike) and fills its empty interior with
// massless particles that count as water for the classification, carry a fluid velocity for
// advection, and emit nothing.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sim/core/vec.h"
#include "sim/diffuse/fluid_state.h"
#include "sim/geometry/solids.h"

namespace spume {

// An enclosed empty interior counts only when it is at least this share of the occupied cells: a
// full cache may enclose a small air pocket (a breaker's barrel), which stays air.
inline constexpr double kNarrowBandShare = 0.05;
// ... and at least this many cells.
inline constexpr size_t kNarrowBandMinCells = 8;

// What the test measured on a frame, and what it decided.
struct InteriorFill {
  float cell = 0.0f;          // the occupancy grid's cell: the support radius h
  size_t occupied_cells = 0;  // cells holding a particle
  size_t enclosed_cells = 0;  // empty cells the air cannot reach
  bool large = false;         // enclosed_cells >= kNarrowBandShare x occupied_cells (and the minimum)
  bool flip_source = false;   // the cache is known to be FLIP (fluid.particles = flip)
  // Depth under the surface (to the nearest cell the air reaches, or the particles' bounds) of the
  // occupied cells bordering the enclosed interior, in m: 10th, 50th and 90th percentile (when large).
  float depth_low = 0.0f, depth_median = 0.0f, depth_high = 0.0f;
  bool narrow_band = false;     // large && flip_source: filled in a run
  bool skipped = false;         // the particles spread over too many cells to look (nothing decided)
  size_t filled = 0;            // particles a run appended to this frame
};

// One line saying what was measured and decided, e.g. "a NARROW BAND: ..." or "full (...)", naming
// the cell used.
std::string describe_interior(const InteriorFill& fill);

// The occupancy grid of cell size `cell` over the particles' bounds, flood-filled from the air side:
// from the layer above the particles (against `gravity`; with no gravity, from every side), through
// empty cells, never into `solids`. The particles' bounds are closed on the other sides, as a FLIP
// domain's walls are, so a band lying against a wall still encloses its interior.
inline constexpr uint32_t kFillerId = UINT32_MAX;

class InteriorFiller {
 public:
  // The test: the particles alone (no solids, which `spume info` does not know), on cells of `cell`.
  InteriorFill examine(const std::vector<Vec3f>& positions, float cell, const Vec3f& gravity, bool flip_source);
  // Appends lattice points of spacing `spacing` in the enclosed cells, and in occupied cells next to
  // them where no particle lies within 0.8 `spacing` (the band's inner edge), with mass 0, id
  // kFillerId and the velocity and motion of the nearest particles (the mean of their cell, carried
  // inwards cell by cell). Returns how many. The caller has decided (examine) that the frame is a band.
  size_t fill(FluidStepState& state, float cell, float spacing, const Vec3f& gravity, const SolidSet* solids);

 private:
  // Grid, particles by cell, kinds and the flood; false when the grid would be too large.
  bool flood(const std::vector<Vec3f>& positions, float cell, const Vec3f& gravity, const SolidSet* solids);

  std::array<int64_t, 3> dims_{};
  Vec3f origin_ = Vec3f::Zero();
  std::vector<uint32_t> cell_of_, start_, members_;
  std::vector<uint8_t> kind_;
  std::vector<uint32_t> queue_;
  std::vector<Vec3f> cell_velocity_, cell_motion_;
};

}  // namespace spume
