#include "container.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace spume {
namespace {

// Pressing in this share of the frames from the first arrival on makes a wall.
constexpr float kWallShare = 0.6f;

const char* side_name(int side) {
  static const char* names[6] = {"-x", "+x", "-y", "+y", "-z", "+z"};
  return names[side];
}

}  // namespace

InferredContainer infer_container(const FluidSurvey& survey, float particle_radius, int up_axis) {
  InferredContainer c;
  const Aabb all = survey.bounds();
  if (survey.frames.empty() || all.empty()) {
    c.summary = "no container inferred: the sequence holds no fluid";
    return c;
  }
  for (int side = 0; side < 6; ++side) {
    const int axis = side / 2;
    const bool low = side % 2 == 0;
    auto reach = [&](const FrameSurvey& f) { return f.sheet[size_t(side)]; };
    c.plane[size_t(side)] = low ? all.min[axis] : all.max[axis];
    if (axis == up_axis && !low) continue;  // no lid
    // The wall's plane: the sheet position most frames agree on (within r), the outermost of equals.
    // Frames whose sheet lies beyond it (spray thrown over a rim) may be at most a quarter.
    const size_t n = survey.frames.size();
    size_t best_support = 0;
    float extreme = reach(survey.frames.front());
    for (const FrameSurvey& candidate : survey.frames) {
      const float e = reach(candidate);
      size_t support = 0;
      for (const FrameSurvey& f : survey.frames) support += std::abs(reach(f) - e) <= particle_radius;
      const bool outer = low ? e < extreme : e > extreme;
      if (support > best_support || (support == best_support && outer)) best_support = support, extreme = e;
    }
    // Within the frames that agree, the outermost sheet: the one closest to the wall.
    const float agreed = extreme;
    for (const FrameSurvey& f : survey.frames)
      if (std::abs(reach(f) - agreed) <= particle_radius) extreme = low ? std::min(extreme, reach(f)) : std::max(extreme, reach(f));
    size_t beyond = 0;
    for (const FrameSurvey& f : survey.frames) beyond += (low ? extreme - reach(f) : reach(f) - extreme) > particle_radius;
    if (4 * beyond > n) continue;
    int first = -1, pressing = 0;
    for (size_t k = 0; k < n; ++k) {
      const bool touches = std::abs(reach(survey.frames[k]) - extreme) <= particle_radius;
      if (touches && first < 0) first = int(k);
      if (first >= 0) pressing += touches;
    }
    const float share = float(pressing) / float(n - size_t(first));
    c.pressed_share[size_t(side)] = share;
    if (share < kWallShare) continue;
    c.wall[size_t(side)] = true;
    // Particle centres stay about r off a wall.
    c.plane[size_t(side)] = low ? extreme - particle_radius : extreme + particle_radius;
  }
  const int floor = 2 * up_axis;
  std::string walls;
  for (int side = 0; side < 6; ++side)
    if (c.wall[size_t(side)]) walls += str(walls.empty() ? "" : ", ", side_name(side), " at ", c.plane[size_t(side)]);
  if (!c.wall[size_t(floor)]) {
    c.summary = str("no container inferred: no floor found (walls: ", walls.empty() ? "none" : walls, ")");
    return c;
  }
  // Sides without a wall are moved out of the way by the sequence's size.
  const float far = 2.0f * (all.max - all.min).maxCoeff() + 1.0f;
  Solid tank;
  tank.kind = Solid::Kind::Tank;
  tank.up_axis = up_axis;
  tank.open_top = true;
  for (int axis = 0; axis < 3; ++axis) {
    tank.min[axis] = c.wall[size_t(2 * axis)] ? c.plane[size_t(2 * axis)] : all.min[axis] - far;
    tank.max[axis] = c.wall[size_t(2 * axis + 1)] ? c.plane[size_t(2 * axis + 1)] : all.max[axis] + far;
  }
  // The open top's rim: as high as the fluid ever goes, so its walls hold what the fluid reached.
  tank.max[up_axis] = all.max[up_axis] + particle_radius;
  c.tank = tank;
  std::string open;
  for (int side = 0; side < 6; ++side)
    if (!c.wall[size_t(side)] && side != 2 * up_axis + 1) open += str(open.empty() ? "" : ", ", side_name(side));
  c.summary = str("container inferred from the fluid: walls ", walls, open.empty() ? "" : str("; open: ", open),
                  "; open top at ", tank.max[up_axis]);
  return c;
}

}  // namespace spume
