#include "sim/scene/velocity_check.h"

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <vector>

#include "sim/core/error.h"

namespace spume {
namespace {

// Particles added or removed move the centroid by where they are, not by any motion: an emitter adding
// 0.6% a frame (SPlisHSPlasH's) already reads as 1.5x. Only intervals of a steady count are compared,
// and only in a sequence whose count holds over most intervals: where it changes in most (a FLIP cache
// reseeding), the intervals where it happens to hold reseeded too, only as many as were removed (a
// Mantaflow dam break read -0.485 on 4 such intervals of 74).
constexpr double kMaxCountChange = 0.001;
constexpr double kMinSteadyShare = 0.5;
constexpr float kMinShiftInRadii = 0.1f;    // a centroid at rest measures nothing
constexpr int kMinIntervals = 3;
constexpr float kAgreement = 1.5f;          // ratios within [1/1.5, 1.5] agree
constexpr float kMinFrontShiftInRadii = 2.0f;  // an extreme must move a particle spacing to be measured
constexpr int kMinFrontPairs = 5;
constexpr int kMinTrackedPairs = 20;
// The top measures the fluid's velocity only where it is a free surface carried by the fluid; where
// fluid arrives from the side (a jet entering a column) it rises while the particles fall. Trusted when
// at least this share of the columns moved the way their stored velocities point.
constexpr double kMinConsistentShare = 2.0 / 3.0;

// Ratios of stored to moved at the fluid's extremes, one per interval, side and column that moved.
std::vector<float> extreme_ratios(const FluidSurvey& survey, double fps, float particle_radius, float velocity_scale,
                                  const Vec3f& gravity) {
  int up_side = -1;  // both surveyed sides (-y, +y)
  if (gravity.squaredNorm() > 0.0f) {
    int axis = 0;
    gravity.cwiseAbs().maxCoeff(&axis);
    up_side = 2 * axis + (gravity[axis] < 0.0f ? 1 : 0);
  }
  std::vector<float> ratios;
  for (size_t k = 0; k + 1 < survey.frames.size(); ++k) {
    const FrameSurvey& a = survey.frames[k];
    const FrameSurvey& b = survey.frames[k + 1];
    if (a.column <= 0.0f || a.column != b.column) continue;  // columns of another size are other columns
    std::map<std::array<int, 3>, const FrameSurvey::ColumnFront*> before;
    for (const FrameSurvey::ColumnFront& c : a.fronts) before[{c.side, c.i, c.j}] = &c;
    for (const FrameSurvey::ColumnFront& c : b.fronts) {
      if (up_side >= 0 && c.side != up_side) continue;
      const auto it = before.find({c.side, c.i, c.j});
      if (it == before.end()) continue;
      const float shift = c.sheet - it->second->sheet;
      if (!(std::fabs(shift) >= kMinFrontShiftInRadii * particle_radius)) continue;
      const float stored = 0.5f * velocity_scale * (it->second->velocity + c.velocity);
      const float moved = shift * float(fps / double(b.frame - a.frame));
      if (std::isfinite(stored)) ratios.push_back(stored / moved);
    }
  }
  return ratios;
}

// Ratios of stored to moved for the particles tracked by id in consecutive frames that moved at least r.
std::vector<float> tracked_ratios(const FluidSurvey& survey, double fps, float particle_radius, float velocity_scale) {
  std::vector<float> ratios;
  for (size_t k = 0; k + 1 < survey.frames.size(); ++k) {
    const FrameSurvey& a = survey.frames[k];
    const FrameSurvey& b = survey.frames[k + 1];
    size_t j = 0;
    for (const FrameSurvey::Tracked& p : a.tracked) {  // both sorted by id
      while (j < b.tracked.size() && b.tracked[j].id < p.id) ++j;
      if (j == b.tracked.size() || b.tracked[j].id != p.id) continue;
      const Vec3f moved = (b.tracked[j].position - p.position) * float(fps / double(b.frame - a.frame));
      if (!(moved.norm() >= particle_radius * float(fps / double(b.frame - a.frame)))) continue;
      const Vec3f stored = 0.5f * velocity_scale * (p.velocity + b.tracked[j].velocity);
      ratios.push_back(stored.dot(moved) / moved.squaredNorm());
    }
  }
  return ratios;
}

// A ratio that is zero, negative, not finite or beyond any plausible unit is no unit and no frame
// rate: velocities pointing against the motion measured say the measure failed (reseeding, fluid
// arriving from elsewhere) or the velocities are not the fluid's; no factor is advised from it.
constexpr float kMaxPlausibleFactor = 1e4f;

VelocityCheck not_measured(VelocityCheck check, const std::string& measured) {
  if (check.ratio == 0.0f) {
    check.note = str("warning: the stored velocities are zero where the fluid moves (0 times", measured,
                     "): every kinetic score (E_k, Eqs. 2 and 7) would be zero; no fluid.velocity_scale or fluid.fps "
                     "changes that, so none is advised");
  } else {
    check.note = str("stored velocities not checked against the motion: they came out ", check.ratio, " times",
                     measured, check.ratio < 0.0f ? ", pointing against the motion" : ", beyond any unit",
                     ", which no unit and no frame rate explain; the measure is not trusted and no "
                     "fluid.velocity_scale or fluid.fps is derived from it");
  }
  check.ratio = NAN;
  check.by_ids = check.by_extremes = false;
  return check;
}

float median(std::vector<float> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace

VelocityCheck check_stored_velocities(const FluidSurvey& survey, double fps, float particle_radius,
                                      float velocity_scale, const Vec3f& gravity) {
  VelocityCheck check;
  std::vector<float> ratios;
  bool any_velocities = false;
  int compared = 0, steady = 0;
  for (size_t k = 0; k + 1 < survey.frames.size(); ++k) {
    const FrameSurvey& a = survey.frames[k];
    const FrameSurvey& b = survey.frames[k + 1];
    any_velocities = any_velocities || a.has_mean_velocity();
    if (!a.has_mean_velocity() || !b.has_mean_velocity() || a.particles == 0 || b.particles == 0) continue;
    ++compared;
    const double change = std::fabs(double(b.particles) - double(a.particles)) / double(a.particles);
    if (change > kMaxCountChange) continue;
    ++steady;
    const Vec3f shift = b.centroid - a.centroid;
    if (!(shift.norm() >= kMinShiftInRadii * particle_radius)) continue;
    const Vec3f motion = shift * float(fps / double(b.frame - a.frame));
    const Vec3f stored = 0.5f * velocity_scale * (a.mean_velocity + b.mean_velocity);
    ratios.push_back(stored.dot(motion) / motion.squaredNorm());
  }
  if (double(steady) < kMinSteadyShare * double(compared)) ratios.clear();  // a reseeding or emitting cache
  check.intervals = int(ratios.size());
  if (!any_velocities) return check;
  const std::vector<float> tracked = check.intervals < kMinIntervals
                                         ? tracked_ratios(survey, fps, particle_radius, velocity_scale)
                                         : std::vector<float>{};
  if (int(tracked.size()) >= kMinTrackedPairs) {
    check.by_ids = true;
    check.intervals = int(tracked.size());
    check.ratio = median(tracked);
  } else if (check.intervals < kMinIntervals) {
    const std::vector<float> fronts = extreme_ratios(survey, fps, particle_radius, velocity_scale, gravity);
    if (int(fronts.size()) < kMinFrontPairs) {
      check.note = str("stored velocities not checked against the motion: ", check.intervals,
                       " frame intervals where the fluid's centroid moves while its particle count holds (within 0.1%, "
                       "in a sequence where it holds over at least half the intervals: ", steady, " of ", compared,
                       "; ", kMinIntervals, " needed), and ", fronts.size(), " where the fluid's top moves at least ",
                       kMinFrontShiftInRadii, " r (", kMinFrontPairs, " needed)");
      return check;
    }
    const double consistent =
        double(std::count_if(fronts.begin(), fronts.end(), [](float q) { return q > 0.0f; })) / double(fronts.size());
    if (consistent < kMinConsistentShare) {
      check.note = str("stored velocities not checked against the motion: the particle count changes, so the "
                       "centroid cannot be used, and the fluid's top (", fronts.size(), " columns and frame intervals "
                       "that moved at least 2 r) moved the way its stored velocities point in only ",
                       100.0 * consistent, "% of them (", 100.0 * kMinConsistentShare, "% needed): there it is fluid "
                       "arriving or leaving, not a free surface carried by the fluid");
      return check;
    }
    check.by_extremes = true;
    check.intervals = int(fronts.size());
    check.ratio = median(fronts);
  } else {
    check.ratio = median(ratios);
  }
  const std::string measured =
      check.by_ids
          ? str(" the motion of the same particles (by id: up to 64 tracked a frame, median over ", check.intervals,
                " particle moves of at least r; the particle count changes, so the centroid cannot be used)")
      : check.by_extremes
          ? str(" the motion of the fluid's top (in columns, the 8 highest particles' stored vertical velocity "
                "against the rise of the 4th highest, median over ", check.intervals, " columns and frame intervals "
                "that moved at least 2 r: a free surface moves with the fluid; the particle count changes, so the "
                "centroid cannot be used)")
          : str(" the velocity of the fluid's centroid (median over ", check.intervals, " frame intervals)");
  const std::string scaled = velocity_scale != 1.0f ? str(" (after fluid.velocity_scale = ", velocity_scale, ")") : "";
  if (!(check.ratio >= 1.0f / kMaxPlausibleFactor && check.ratio <= kMaxPlausibleFactor))
    return not_measured(check, measured);
  if (check.ratio >= 1.0f / kAgreement && check.ratio <= kAgreement) {
    check.agrees = true;
    check.note = str("stored velocities", scaled, " agree with the motion: ", check.ratio, " times", measured);
    return check;
  }
  // Advice only within what the keys take (fluid.velocity_scale (0, 1e6], fluid.fps [1e-3, 1e5]).
  const double scale_advice = double(velocity_scale) / double(check.ratio), fps_advice = fps * double(check.ratio);
  const bool scale_ok = scale_advice > 0.0 && scale_advice <= 1e6, fps_ok = fps_advice >= 1e-3 && fps_advice <= 1e5;
  check.note = str("warning: the stored velocities", scaled, " are ", check.ratio, " times", measured,
                   ", at fluid.fps = ", fps, ": every kinetic score (E_k, Eqs. 2 and 7) would be off by that factor.",
                   scale_ok ? str(" If the cache stores velocities in other units, set fluid.velocity_scale = ",
                                  scale_advice, ";")
                            : std::string(),
                   fps_ok ? str(" if its frame rate is not ", fps, " per second, set fluid.fps (--fps) to ", fps_advice)
                          : std::string());
  return check;
}

}  // namespace spume
