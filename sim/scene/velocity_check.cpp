#include "sim/scene/velocity_check.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/core/error.h"

namespace spume {
namespace {

// Particles added or removed move the centroid by where they are, not by any motion: an emitter adding
// 0.6% a frame (SPlisHSPlasH's) already reads as 1.5x. Only intervals of a steady count are compared.
constexpr double kMaxCountChange = 0.001;
constexpr float kMinShiftInRadii = 0.1f;    // a centroid at rest measures nothing
constexpr int kMinIntervals = 3;
constexpr float kAgreement = 1.5f;          // ratios within [1/1.5, 1.5] agree

}  // namespace

VelocityCheck check_stored_velocities(const FluidSurvey& survey, double fps, float particle_radius,
                                      float velocity_scale) {
  VelocityCheck check;
  std::vector<float> ratios;
  bool any_velocities = false;
  for (size_t k = 0; k + 1 < survey.frames.size(); ++k) {
    const FrameSurvey& a = survey.frames[k];
    const FrameSurvey& b = survey.frames[k + 1];
    any_velocities = any_velocities || a.has_mean_velocity();
    if (!a.has_mean_velocity() || !b.has_mean_velocity() || a.particles == 0 || b.particles == 0) continue;
    const double change = std::fabs(double(b.particles) - double(a.particles)) / double(a.particles);
    if (change > kMaxCountChange) continue;
    const Vec3f shift = b.centroid - a.centroid;
    if (!(shift.norm() >= kMinShiftInRadii * particle_radius)) continue;
    const Vec3f motion = shift * float(fps / double(b.frame - a.frame));
    const Vec3f stored = 0.5f * velocity_scale * (a.mean_velocity + b.mean_velocity);
    ratios.push_back(stored.dot(motion) / motion.squaredNorm());
  }
  check.intervals = int(ratios.size());
  if (!any_velocities) return check;
  if (check.intervals < kMinIntervals) {
    check.note = str("stored velocities not checked against the motion: ", check.intervals,
                     " frame intervals where the fluid's centroid moves while its particle count holds (within 0.1%; ",
                     kMinIntervals, " needed)");
    return check;
  }
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  check.ratio = ratios[ratios.size() / 2];
  const std::string scaled = velocity_scale != 1.0f ? str(" (after fluid.velocity_scale = ", velocity_scale, ")") : "";
  if (check.ratio >= 1.0f / kAgreement && check.ratio <= kAgreement) {
    check.note = str("stored velocities", scaled, " agree with the motion: ", check.ratio,
                     " times the velocity of the fluid's centroid (median over ", check.intervals, " frame intervals)");
    return check;
  }
  check.note = str("warning: the stored velocities", scaled, " are ", check.ratio,
                   " times the motion of the fluid (the mean stored velocity against the centroid's displacement "
                   "times fluid.fps = ", fps, ", median over ", check.intervals, " frame intervals): every kinetic "
                   "score (E_k, Eqs. 2 and 7) would be off by that factor. If the cache stores velocities in other "
                   "units, set fluid.velocity_scale = ", velocity_scale / check.ratio, "; if its frame rate is not ",
                   fps, " per second, set fluid.fps (--fps) to ", fps * check.ratio);
  return check;
}

}  // namespace spume
