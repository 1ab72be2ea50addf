#pragma once
// Everything the fluid solver carries from one step to the next, so that a run can stop after a
// frame and a later one continue from there with the same bytes as one uninterrupted run
// (FluidSolver::restart_state / restore).
//
// Carried: the particles in the solver's own (cell-sorted) order, which fixes the order of every
// later sum; their ids, positions and velocities; the warm-start pressures when warm_start is on
// (otherwise never read); the time and the last step, which the next step's divergence solve and
// CFL estimate use; and the counters behind solver_stats.csv, with the step cap retries lowered.
// Not carried, because the next step rebuilds them from the above: neighbour grid and pairs,
// densities, DFSPH factors, accelerations, boundary particles (kinematic solids are placed by their
// motion at the restored time). Dynamic bodies carry their poses: Bullet starts every stretch the
// solver advances (a frame) afresh from them, contact caches and warm-started impulses cleared, so
// the poses are all of its state a later step depends on.
//
// File (.spr), little-endian, no padding, header 184 bytes:
//   offset   0  char[8]  magic "SPUMERS1"
//   offset   8  u32      version (3; 2 had no bodies, and is read as a scene without them; 1 had no
//                        retries and step cap)
//   offset  12  i32      frame index the state belongs to
//   offset  16  f64      time (s)
//   offset  24  f64      the last step, dt_prev (s)
//   offset  32  f32      particle radius (m)
//   offset  36  u32      flags: bit 0 warm-start arrays present (other bits must be 0)
//   offset  40  u64      particle count n
//   offset  48  char[16] digest of what the state was made from (the caller's; e.g. the scene keys)
//   offset  64  u64[8]   steps, density iterations, divergence iterations, unconverged density solves,
//                        unconverged divergence solves, corrections, steps clamped to min_dt, retries
//   offset 128  f64[7]   sum of dt, last density error, largest density error, last divergence error,
//                        smallest dt, largest dt, the step cap (s; retries lower it for good)
//   then ids u32[n], positions f32[3n], velocities f32[3n],
//        (bit 0) density warm start f32[n], divergence warm start f32[n], all in solver order,
//   then u32 body count m and per body (56 bytes): u32 solid index, f32[3] centre, f32[4] orientation
//        (w, x, y, z), f32[3] velocity, f32[3] angular velocity (BodyPose),
//   then u32 CRC-32 (zlib crc32) of every byte before it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sim/core/vec.h"
#include "sim/fluid/solver_counters.h"
#include "sim/geometry/solids.h"

namespace spume {

struct FluidRestartState {
  int32_t frame = 0;
  double time = 0.0;     // s
  double dt_prev = 0.0;  // s
  float particle_radius = 0.0f;
  std::string digest;    // up to 16 characters
  SolverCounters counters;  // behind SolverStats (solver_counters.h)
  // Per particle, in solver order; the warm-start arrays empty when warm start is off.
  std::vector<uint32_t> ids;
  std::vector<Vec3f> positions, velocities;
  std::vector<float> density_warm, divergence_warm;
  std::vector<BodyPose> bodies;  // the dynamic bodies, in body order

  size_t size() const { return ids.size(); }
};

constexpr uint32_t kRestartVersion = 3;

void write_restart_state(const std::filesystem::path& path, const FluidRestartState& state);
// Verifies magic, version, flags, size, CRC and that every value is finite; Error names the file.
FluidRestartState read_restart_state(const std::filesystem::path& path);

}  // namespace spume
