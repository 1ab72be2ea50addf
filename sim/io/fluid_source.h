#pragma once
// Where fluid frames come from: particle files on disk (SPlisHSPlasH, Houdini, VTK, PLY, spume's own
// caches) or, in scenes that say so, spume's solver. The diffuse simulator only sees FluidFrames.
#include <memory>
#include <string>
#include <vector>

#include "sim/core/frames.h"
#include "sim/io/fluid_read_options.h"

namespace spume {

class FluidSource {
 public:
  virtual ~FluidSource() = default;
  virtual std::vector<int> frame_numbers() const = 0;  // sorted, available frames (gaps filled if allowed)
  virtual std::vector<int> file_frames() const = 0;    // sorted, the frames that have a file
  virtual FluidFrame load(int frame) = 0;              // frame.time = frame / fps unless the source knows better
  virtual std::string describe() const = 0;
};

// Files named by a pattern with %d, %04d, #### or $F4 (e.g. "cache/ParticleData_Fluid_%d.bgeo"). With
// `allow_gaps`, frames missing between the first and last file are available too, interpolated
// between the files on either side (interpolate_frames); without, they are simply not listed (the
// stages refuse a range with a gap, naming the missing frame).
// `velocity_scale` multiplies the stored velocities as they are read (fluid.velocity_scale, or a
// Mantaflow cache's units: io/fluid_import.h); `read` turns a Z-up cache and picks a VDB grid.
std::unique_ptr<FluidSource> make_file_source(const std::string& pattern, double fps, bool allow_gaps = false,
                                              float velocity_scale = 1.0f, const FluidReadOptions& read = {});

// Frame numbers missing between consecutive entries of sorted `frames`.
std::vector<int> missing_frames(const std::vector<int>& frames);

// The fluid at `frame` (time `time`, between a.time and b.time): positions (and velocities, when
// both have them) interpolated linearly between a and b for particles matched by id (by index when
// neither has ids, the counts agree and the order is kept: index_order_mismatch); particles only a
// has move on with their velocity; particles only b has are left out.
FluidFrame interpolate_frames(const FluidFrame& a, const FluidFrame& b, int frame, double time);

}  // namespace spume
