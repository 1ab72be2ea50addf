#pragma once
// The container a fluid cache was simulated in, inferred from the sequence alone: an axis-aligned
// side is a wall when the fluid presses a sheet of particles (4 or more within r of its extreme)
// against one plane there in at least 60% of the frames from the first time it arrives, and no
// sheet goes beyond it. Lone particles beyond (spray over a rim) are ignored. Caches from other simulators seldom carry
// their geometry; without walls the diffuse model cannot tell a wet wall from open air.
#include <array>
#include <optional>
#include <string>

#include "io/fluid_survey.h"
#include "geometry/solids.h"

namespace spume {

struct InferredContainer {
  // Per side (-x, +x, -y, +y, -z, +z): a wall was found, and where (the plane; for sides without a
  // wall, the fluid's extreme over the sequence).
  std::array<bool, 6> wall{};
  std::array<float, 6> plane{};
  // Share of the frames, from the first that reaches the side, in which the fluid presses on it.
  std::array<float, 6> pressed_share{};
  std::optional<Solid> tank;  // set when the floor was found; sides without walls lie far away
  std::string summary;        // one line for the log: which walls, where
};

// `particle_radius`: the fluid's r (particle centres rest about r from a wall); `up_axis`: opposite
// gravity. A lid is never inferred (a fluid at rest presses on its own top too): the tank is open.
InferredContainer infer_container(const FluidSurvey& survey, float particle_radius, int up_axis);

}  // namespace spume
