#include "container.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace spume {
namespace {

// A sheet, not a few stray particles: what the side of a small block holds already.
constexpr uint64_t kSheet = 16;
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
    const float extreme = low ? all.min[axis] : all.max[axis];
    c.plane[size_t(side)] = extreme;
    if (axis == up_axis && !low) continue;  // no lid
    int first = -1, pressing = 0;
    for (size_t k = 0; k < survey.frames.size(); ++k) {
      const FrameSurvey& f = survey.frames[k];
      const float reach = low ? f.bounds.min[axis] : f.bounds.max[axis];
      const bool touches = std::abs(reach - extreme) <= particle_radius && f.pressed[size_t(side)] >= kSheet;
      if (touches && first < 0) first = int(k);
      if (first >= 0) pressing += touches;
    }
    if (first < 0) continue;
    const float share = float(pressing) / float(survey.frames.size() - size_t(first));
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
