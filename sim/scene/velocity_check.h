#pragma once
// Stored velocities against the motion they should describe. A cache in other units (Mantaflow
// stores grid units), or a wrong fluid.fps, makes every kinetic score wrong by the same factor and
// nothing else shows it. Over a frame interval the mean stored velocity of a fixed set of equal
// particles is exactly the velocity of their centroid, so the survey's per-frame means and centroids
// measure the factor without ids and without reading any frame again.
#include <string>

#include "sim/io/fluid_survey.h"

namespace spume {

struct VelocityCheck {
  int intervals = 0;   // frame intervals compared
  float ratio = NAN;   // median of stored / motion over them (NaN when none could be compared)
  std::string note;    // for the log: a warning when they disagree, else what was found ("" if nothing)
};

// Compares, for each interval between surveyed frames whose counts differ by under 0.1% and whose
// centroid moved at least r/10, the mean of the two frames' mean stored velocities (times
// `velocity_scale`) projected on the centroid's motion (displacement x fps / frames apart). The
// velocities and the motion agree when the median ratio lies within [2/3, 3/2]; 3 intervals at least.
VelocityCheck check_stored_velocities(const FluidSurvey& survey, double fps, float particle_radius,
                                      float velocity_scale);

}  // namespace spume
