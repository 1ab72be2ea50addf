#pragma once
// Whether the tanks a scene gives hold its fluid files. A tank is the container the fluid was
// simulated in; fluid lying outside it (a tank typed at the wrong place, in other units, on other
// axes) would make the diffuse model delete or push out everything it makes, frame after frame.
//
// A particle lies outside when its centre is beyond every tank's walls by more than one particle
// spacing (2r; a simulator keeps particle centres about r inside, some let them touch), the floor and
// the sides only: above an open top is inside. A frame is counted only when its survey shows a sheet
// of 4 particles or more beyond a wall (io/fluid_survey.h), so a few strays are never read for. In a
// frame that is counted, more than 1% of its particles outside is an error; fewer (particles that
// leaked through a wall) is a warning with the count. Static tanks only (a moving tank is not checked).
#include <string>

#include "sim/geometry/solids.h"
#include "sim/io/fluid_survey.h"

namespace spume {

constexpr float kTankOutsideShare = 0.01f;  // more than this share of a frame outside: an error

// Throws Error naming the tank, the frame and how much of its fluid lies outside; returns a warning
// line for a few particles outside, or "" when the tanks hold the fluid (or there are none).
std::string check_tanks_hold_fluid(const FluidSurvey& survey, const SolidSet& solids, float particle_radius);

}  // namespace spume
