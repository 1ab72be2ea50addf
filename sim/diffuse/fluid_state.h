#pragma once
// The fluid as one diffuse step sees it: particles at time t, interpolated between two frames that
// are matched by particle id (counts may change between frames).
#include <cstdint>
#include <string>
#include <vector>

#include "sim/core/frames.h"

namespace spume {

// Links frame k to frame k+1: for each particle of k, its index in k+1 or -1.
struct FramePair {
  const FluidFrame* current = nullptr;
  const FluidFrame* next = nullptr;  // null at the last frame
  std::vector<int32_t> next_index;
  double frame_dt = 0.0;             // s between the two frames
  // Why the particles of frames without ids were left unpaired ("" when they were paired): their
  // counts differ, or index i of the next frame is not where particle i went (MODEL.md §8.16).
  std::string unpaired_because;
};

// Frames with ids are joined on id. Without ids a particle is paired by index only when the counts
// agree and the index order is kept: the median distance from where particle i's stored velocity (or,
// without one, its position) puts it to index i of the next frame must be under a quarter of the
// median distance between unrelated particles (i against i + n/2). Otherwise nothing is paired, and
// interpolate_fluid moves every particle with its stored velocity.
FramePair pair_frames(const FluidFrame& current, const FluidFrame* next, double frame_dt);

// Plain arrays for one step [t, t + dt].
struct FluidStepState {
  std::vector<Vec3f> positions;         // x_f(t), m
  std::vector<Vec3f> velocities;        // v_f(t) for the potentials, m/s
  std::vector<Vec3f> motion;            // (x_f(t+dt) - x_f(t)) / dt, the advecting velocity, m/s
  std::vector<float> masses;            // kg
  std::vector<uint32_t> ids;
};

// State at fraction s in [0, 1) of the interval between the pair's frames. Particles with no match in
// the next frame move with their own velocity; without velocity attributes, velocities are frame
// differences, and a particle with neither has zero velocity. A particle without a usable mass (none in
// the file, or one of 0 or less: core/unusable_masses.h) takes `uniform_mass`.
void interpolate_fluid(const FramePair& pair, float s, float uniform_mass, FluidStepState& out);

}  // namespace spume
