#pragma once
// The container a fluid cache was simulated in, inferred from the sequence alone. Caches from other
// simulators seldom carry their geometry; without walls the diffuse model cannot tell a wet wall from
// open air. A fluid merely having an extreme is no evidence of a wall: a block falling freely keeps
// flat sides too. An axis-aligned side is a wall only when the fluid was seen *stopped* there:
//  1. its sheet (the 4th outermost particle, so strays do not count) lies within r of one plane in
//     at least 60% of the frames from the first time it gets there, and in at least 3 frames, and
//     goes beyond that plane in at most a quarter of the frames (spray thrown over a rim);
//  2. and either the fluid ARRIVED there: in an earlier frame its sheet was at least 2r inside, so it
//     moved towards the plane and stayed; or it was there from the start and is HELD there: the fluid
//     sits on a floor (the floor itself needs no floor) and the side stays put while the fluid flows,
//     where a free fluid would spread;
//  3. and the flow went on while it stayed: an extent of the fluid (sheet to sheet) or its centroid
//     changed by 2r or more (a puddle that stopped spreading has stopped flowing: no wall at its rim).
// A fluid at rest gets no walls, nor does one falling freely (its bottom never stays, and nothing
// holds it up against its flat sides); a moving piston is left open.
// A lid is never inferred (a fluid at rest presses on its own top too): the tank is open. Without a
// floor there is no tank.
#include <array>
#include <optional>
#include <string>

#include "sim/io/fluid_survey.h"
#include "sim/geometry/solids.h"

namespace spume {

struct InferredContainer {
  // Per side (-x, +x, -y, +y, -z, +z): a wall was found, and where (the plane; for sides without a
  // wall, the fluid's extreme over the sequence).
  std::array<bool, 6> wall{};
  std::array<float, 6> plane{};
  // Share of the frames, from the first that reaches the side's plane, in which the fluid is at it.
  std::array<float, 6> pressed_share{};
  // Per side, why it is or is not a wall, for the log ("reached in frame 12, at it in 85% of the
  // frames since", "no evidence: ...").
  std::array<std::string, 6> why;
  std::optional<Solid> tank;  // set when the floor was found; sides without walls lie far away
  bool closed = false;        // the floor and all four sides are walls (the tank has no far side)
  std::string summary;        // one line for the log: which walls, where and why; what is open and why
};

// `particle_radius`: the fluid's r (particle centres rest about r from a wall); `up_axis`: opposite
// gravity. Frames with fewer than 4 particles (empty ones too) hold no sheet and are left out.
InferredContainer infer_container(const FluidSurvey& survey, float particle_radius, int up_axis);

}  // namespace spume
