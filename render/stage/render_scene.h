#pragma once
// What the renderer needs of a scene, and nothing of how it was simulated: where its outputs are
// (io/cache_layout.h), which frames it has and where their fluid comes from, the solids and the
// dynamic bodies' track, the fluid's bounds over the whole sequence (camera, ground), and a digest of
// everything the simulation was made from (part of each frame's record). The spume command builds it
// from the simulation scene (render/app/scene/scene_render.h); the stage only reads caches.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "sim/geometry/body_track.h"
#include "sim/geometry/solids.h"
#include "sim/io/fluid_source.h"

namespace spume {

struct RenderScene {
  std::string name;
  std::filesystem::path scene_out;     // OUT/<scene>
  double fps = 0.0;                    // set by the builder from the scene
  Vec3f up = Vec3f::UnitY();           // opposite gravity
  Vec3f gravity = Vec3f(0.0f, -9.81f, 0.0f);  // m/s^2: spray's paths in the motion blur
  std::unique_ptr<FluidSource> fluid;  // the fluid frames (the solver's caches or the user's files)
  std::string fluid_pattern;           // their file pattern, for frame records
  std::vector<int> frames;             // the frames there are, sorted
  SolidSet solids;                     // as drawn (an inferred tank included)
  BodyTrack bodies;                    // the dynamic solids' poses (empty: none)
  Aabb fluid_bounds;                   // over every frame of the sequence
  std::string sequence_digest;         // of the simulation keys and every input file
};

}  // namespace spume
