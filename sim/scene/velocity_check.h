#pragma once
// Stored velocities against the motion they should describe. A cache in other units (Mantaflow
// stores grid units), or a wrong fluid.fps, makes every kinetic score wrong by the same factor and
// nothing else shows it. Over a frame interval the mean stored velocity of a fixed set of equal
// particles is exactly the velocity of their centroid, so the survey's per-frame means and centroids
// measure the factor without ids and without reading any frame again. Where particles are added or
// removed every frame (FLIP solvers reseed; emitters), the centroid moves by where they are: there the
// fluid's extremes are used instead, since a free surface moves with the fluid at its outermost point
// (the kinematic condition), which no reseeding inside changes.
#include <string>

#include "sim/io/fluid_survey.h"

namespace spume {

struct VelocityCheck {
  int intervals = 0;   // frame intervals compared (by the centroid; by the extremes: intervals x sides x columns)
  bool by_ids = false;       // the count changed too often for the centroid: measured on particles tracked by id
  bool by_extremes = false;  // the count changed too often for the centroid: measured at the fluid's extremes
  float ratio = NAN;   // median of stored / motion over them (NaN when none could be compared)
  bool agrees = false; // the ratio lies within [2/3, 3/2]
  std::string note;    // for the log: a warning when they disagree, else what was found ("" if nothing)
};

// Compares, for each interval between surveyed frames whose counts differ by under 0.1% and whose
// centroid moved at least r/10, the mean of the two frames' mean stored velocities (times
// `velocity_scale`) projected on the centroid's motion (displacement x fps / frames apart). The
// velocities and the motion agree when the median ratio lies within [2/3, 3/2]; 3 intervals at least,
// in a sequence whose count holds over at least half its intervals (where it changes in most, a FLIP
// cache reseeding, the intervals where it happens to hold were reseeded too).
//
// A median that is zero, negative or beyond 1e4 either way advises nothing: all zero is said as such;
// the others say the measure failed (no unit and no frame rate make velocities point against the
// motion). Advice stays within the keys' ranges.
//
// With fewer such intervals and ids in the files, the particles tracked by id (FrameSurvey::tracked)
// are compared one by one where they moved at least r between consecutive frames: the mean of the two
// frames' stored velocities projected on the motion; 20 at least.
//
// Without ids, the fluid's top (FrameSurvey::fronts, on the side facing up against `gravity`; both y
// sides without gravity; nothing when gravity is along x or z, since only the y sides are surveyed):
// each interval and column whose extreme (4th outermost particle) moved at least 2 r compares the mean
// of the two frames' velocities there (the 8 outermost particles' stored velocity along y) with the
// extreme's displacement x fps / frames apart; 5 at least. Only the top: the other sides of a FLIP
// cache are often the inner edge of its narrow band or a wall, which move with reseeding, not with the
// fluid (on the Mantaflow jet the sides' medians ranged from -0.03 to 0.25 against 0.84 on top).
// Trusted only when at least 2/3 of them moved the way their stored velocities point (a jet entering a
// column raises its top while it falls: 28% on SPlisHSPlasH's emitter, 75% on the Mantaflow jet); the
// median outvotes columns where the extreme is not a free surface (a crest sliding out of its column).
VelocityCheck check_stored_velocities(const FluidSurvey& survey, double fps, float particle_radius,
                                      float velocity_scale, const Vec3f& gravity = Vec3f(0.0f, -9.81f, 0.0f));

}  // namespace spume
