#include "sim/scene/tank_fit.h"

#include <vector>

#include "sim/core/error.h"
#include "sim/io/frame_pattern.h"
#include "sim/io/particle_file.h"

namespace spume {
namespace {

std::string box_text(const Vec3f& min, const Vec3f& max) {
  return str("[", min.x(), ", ", min.y(), ", ", min.z(), "] - [", max.x(), ", ", max.y(), ", ", max.z(), "] m");
}

// Whether [lo, hi] lies within the tank's walls grown by `slack` (an open top bounds nothing).
bool within(const Solid& tank, const Vec3f& lo, const Vec3f& hi, float slack) {
  for (int a = 0; a < 3; ++a) {
    if (lo[a] < tank.min[a] - slack) return false;
    if (!(tank.open_top && a == tank.up_axis) && hi[a] > tank.max[a] + slack) return false;
  }
  return true;
}

}  // namespace

std::string check_tanks_hold_fluid(const FluidSurvey& survey, const SolidSet& solids, float particle_radius) {
  std::vector<Solid> tanks;
  for (const Solid& s : solids.solids())
    if (s.kind == Solid::Kind::Tank && !s.motion.moving()) tanks.push_back(s);
  if (tanks.empty()) return "";
  const float slack = 2.0f * particle_radius;
  auto held = [&](const Vec3f& lo, const Vec3f& hi) {
    for (const Solid& t : tanks)
      if (within(t, lo, hi, slack)) return true;
    return false;
  };
  const std::string which =
      tanks.size() == 1 ? str("the tank ", box_text(tanks[0].min, tanks[0].max)) : str("the scene's ", tanks.size(), " tanks");

  size_t worst_outside = 0, worst_particles = 0;
  int worst_frame = 0;
  for (const FrameSurvey& f : survey.frames) {
    if (!f.has_sheet()) continue;
    const Vec3f sheet_lo(f.sheet[0], f.sheet[2], f.sheet[4]), sheet_hi(f.sheet[1], f.sheet[3], f.sheet[5]);
    if (held(sheet_lo, sheet_hi)) continue;
    const FluidFrame frame = read_fluid_file(expand_frame_pattern(survey.pattern, f.frame), survey.read);
    size_t outside = 0;
    for (const Vec3f& p : frame.positions) outside += !held(p, p);
    if (float(outside) > kTankOutsideShare * float(frame.size())) {
      const Aabb all = survey.bounds();
      fail(which, " does not hold the fluid: in frame ", f.frame, ", ", outside, " of its ", frame.size(),
           " particles (", int(std::lround(100.0 * double(outside) / double(frame.size()))),
           "%) lie more than 2r = ", slack, " m outside its walls (the fluid spans ", box_text(all.min, all.max),
           " over the sequence; more than ", 100.0f * kTankOutsideShare,
           "% outside is an error). Give the corners of the container the fluid was simulated in "
           "(solids[].min and max, or --tank X0,Y0,Z0,X1,Y1,Z1), or infer it (--tank auto)");
    }
    if (outside * worst_particles > worst_outside * frame.size() || worst_particles == 0)
      worst_outside = outside, worst_particles = frame.size(), worst_frame = f.frame;
  }
  if (worst_outside == 0) return "";
  return str("warning: ", which, ": in frame ", worst_frame, ", ", worst_outside, " of ", worst_particles,
             " fluid particles lie more than 2r = ", slack, " m outside its walls (leaked through them, or the tank "
             "is a little small; up to ", 100.0f * kTankOutsideShare, "% of a frame is taken for leaks, more is an error)");
}

}  // namespace spume
