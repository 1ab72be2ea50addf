#pragma once
// The dynamic solids' trajectories as the fluid solver computed them: one set of poses per fluid
// frame. The solver alone integrates the rigid bodies; the diffuse stage and the renderer replay
// them from this track, so all three see the cubes of a collapsing tower in the same places.
#include <vector>

#include "sim/geometry/solids.h"

namespace spume {

struct BodyTrack {
  double fps = 0.0;
  int first_frame = 0;
  std::vector<std::vector<BodyPose>> frames;  // frames[k]: poses at (first_frame + k) / fps

  bool empty() const { return frames.empty(); }
  // Poses at time t (s): positions and velocities linear, orientations slerped between the two
  // frames around t; clamped to the first and last frame outside the track.
  std::vector<BodyPose> at_time(double t) const;
  // Throws Error naming `source` when frames list different bodies or fps is not positive.
  void validate(const std::string& source) const;
};

// `solids` at time t: kinematic solids moved by their motions, dynamic ones at the track's poses
// (at their initial pose when the track is empty).
SolidSet solids_at_time(const SolidSet& solids, const BodyTrack& track, double t);

}  // namespace spume
