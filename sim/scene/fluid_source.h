#pragma once
// Where fluid frames come from: particle files on disk (SPlisHSPlasH, Houdini, VTK, PLY, spume's own
// caches) or, in scenes that say so, spume's solver. The diffuse simulator only sees FluidFrames.
#include <memory>
#include <string>
#include <vector>

#include "core/frames.h"

namespace spume {

class FluidSource {
 public:
  virtual ~FluidSource() = default;
  virtual std::vector<int> frame_numbers() const = 0;  // sorted, available frames
  virtual FluidFrame load(int frame) = 0;              // frame.time = frame / fps unless the source knows better
  virtual std::string describe() const = 0;
};

// Files named by a pattern with %d, %04d or #### (e.g. "cache/ParticleData_Fluid_%d.bgeo").
std::unique_ptr<FluidSource> make_file_source(const std::string& pattern, double fps);

}  // namespace spume
