#pragma once
// Narrow-band caches (MODEL.md §9.1): FLIP solvers (Blender's Mantaflow, Houdini) often keep particles
// only in a band a few cells thick under the liquid's surface, the interior being carried by their
// grids. A bubble inside would count no fluid neighbours and become spray. This finds such an empty
// interior and fills it with massless particles that count as water for the classification, carry a
// fluid velocity for advection, and emit nothing.
#include <cstdint>
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

struct InteriorFill {
  size_t occupied_cells = 0;  // cells of size `cell` holding a particle
  size_t enclosed_cells = 0;  // empty cells the air cannot reach
  size_t filled = 0;          // particles appended (0 unless narrow_band)
  bool narrow_band = false;   // enclosed_cells >= kNarrowBandShare x occupied_cells (and the minimum)
  bool skipped = false;       // the particles spread over too many cells to look (nothing filled)
};

// Occupancy grid of cell size `cell` over the particles' bounds, flood-filled from the air side:
// from the layer above the particles (against `gravity`; with no gravity, from every side), through
// empty cells, never into `solids`. The particles' bounds are closed on the other sides, as a FLIP
// domain's walls are, so a band lying against a wall still encloses its interior. Where the
// enclosed empty cells make a narrow band, lattice points of spacing `spacing` are appended in them,
// and in occupied cells next to them where no particle lies within 0.8 `spacing` (the band's inner edge),
// with mass 0, id kFillerId and the velocity and motion of the nearest particles (the mean of their
// cell, carried inwards cell by cell). Otherwise `state` is left as it was, bit for bit.
inline constexpr uint32_t kFillerId = UINT32_MAX;

class InteriorFiller {
 public:
  InteriorFill fill(FluidStepState& state, float cell, float spacing, const Vec3f& gravity, const SolidSet* solids);

 private:
  std::vector<uint32_t> cell_of_, start_, members_;
  std::vector<uint8_t> kind_;
  std::vector<uint32_t> queue_;
  std::vector<Vec3f> cell_velocity_, cell_motion_;
};

}  // namespace spume
