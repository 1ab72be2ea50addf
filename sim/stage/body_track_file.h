#pragma once
// The body track on disk: OUT/<scene>/fluid/bodies.csv, written by the fluid stage of a scene with
// dynamic solids. One row per frame and body:
//   frame,solid,px,py,pz,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
// (centre in m, orientation body -> world, velocity in m/s, angular velocity in rad/s, world frame),
// with 9 significant digits so that every float reads back exactly.
#include <filesystem>

#include "sim/geometry/body_track.h"
#include "sim/io/cache_layout.h"
#include "sim/scene/sim_scene.h"

namespace spume {

void write_body_track(const std::filesystem::path& path, const BodyTrack& track);
// Throws Error naming the file and line for anything malformed.
BodyTrack read_body_track(const std::filesystem::path& path, double fps);

// The track a scene's later stages replay: empty when the scene has no dynamic solid; otherwise read
// from the fluid stage's output, and an error when the scene's fluid does not come from the solver
// (only the solver moves dynamic bodies) or the file is missing.
BodyTrack scene_body_track(const SimScene& scene, const std::filesystem::path& scene_out);

}  // namespace spume
