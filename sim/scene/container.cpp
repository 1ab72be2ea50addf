#include "sim/scene/container.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/core/error.h"

namespace spume {
namespace {

// At the plane in this share of the frames from the first arrival on, and in this many frames at least.
constexpr float kWallShare = 0.6f;
constexpr size_t kFramesAtWall = 3;
// In units of r: how far inside the sheet must have been to have arrived, and how much an extent
// or its centroid must change for the fluid to have flowed (one particle spacing: more than a sheet's jitter).
constexpr float kArrival = 2.0f;
constexpr float kFlow = 2.0f;

const char* side_name(int side) {
  static const char* names[6] = {"-x", "+x", "-y", "+y", "-z", "+z"};
  return names[side];
}
const char* axis_name(int axis) {
  static const char* names[3] = {"x", "y", "z"};
  return names[axis];
}

// A side's sheet as a distance outwards (larger is further out), so both sides read alike.
float outward(const FrameSurvey& f, int side) { return side % 2 == 0 ? -f.sheet[size_t(side)] : f.sheet[size_t(side)]; }

// How much the fluid flowed over frames [b, e]: the largest change of an extent (sheet to sheet, on
// any axis: a change of shape) or of its centroid (a flow that keeps the extents, such as a pool
// filling from a jet). A fluid at rest changes neither.
float flow(const std::vector<const FrameSurvey*>& frames, size_t b, size_t e) {
  float change = 0.0f;
  for (size_t axis = 0; axis < 3; ++axis) {
    float lo = INFINITY, hi = -INFINITY, c_lo = INFINITY, c_hi = -INFINITY;
    for (size_t k = b; k <= e; ++k) {
      const float extent = frames[k]->sheet[2 * axis + 1] - frames[k]->sheet[2 * axis];
      lo = std::min(lo, extent), hi = std::max(hi, extent);
      c_lo = std::min(c_lo, frames[k]->centroid[int(axis)]), c_hi = std::max(c_hi, frames[k]->centroid[int(axis)]);
    }
    change = std::max({change, hi - lo, c_hi - c_lo});
  }
  return change;
}

struct SideVerdict {
  bool wall = false;
  float sheet = 0.0f;  // the plane the sheet keeps to, world coordinate
  float share = 0.0f;
  std::string why;
};

// `frames`: the frames that hold a sheet, in order. `floor_is_wall`: for a side other than the floor,
// whether the floor was found (a fluid held up by nothing presses on no side).
SideVerdict judge_side(const std::vector<const FrameSurvey*>& frames, int side, float r, bool is_floor,
                       bool floor_is_wall) {
  SideVerdict v;
  const size_t n = frames.size();
  auto o = [&](size_t k) { return outward(*frames[k], side); };
  // The plane: the sheet position most frames agree on (within r), the outermost of equals; then,
  // within the frames that agree, the outermost sheet (the one closest to the wall).
  size_t best_support = 0;
  float plane = o(0);
  for (size_t c = 0; c < n; ++c) {
    size_t support = 0;
    for (size_t k = 0; k < n; ++k) support += std::abs(o(k) - o(c)) <= r;
    if (support > best_support || (support == best_support && o(c) > plane)) best_support = support, plane = o(c);
  }
  const float agreed = plane;
  for (size_t k = 0; k < n; ++k)
    if (std::abs(o(k) - agreed) <= r) plane = std::max(plane, o(k));
  v.sheet = side % 2 == 0 ? -plane : plane;
  const std::string where = str(axis_name(side / 2), " = ", v.sheet);

  size_t first = n, last = 0, at = 0, beyond = 0;
  for (size_t k = 0; k < n; ++k) {
    const bool touches = std::abs(o(k) - plane) <= r;
    if (touches) first = std::min(first, k), last = k, ++at;
    beyond += o(k) - plane > r;
  }
  v.share = float(at) / float(n - first);
  if (v.share < kWallShare) {
    v.why = str("moves: at ", where, " in only ", int(std::lround(100.0f * v.share)), "% of the frames since frame ",
                frames[first]->frame);
    return v;
  }
  if (4 * beyond > n) {
    v.why = str("the fluid goes past ", where, " in ", beyond, " of ", n, " frames");
    return v;
  }
  if (at < kFramesAtWall) {
    v.why = str("weak evidence: at ", where, " in only ", at, at == 1 ? " frame" : " frames", " (from frame ",
                frames[first]->frame, ")");
    return v;
  }
  bool arrived = false;
  for (size_t k = 0; k < first; ++k) arrived = arrived || o(k) <= plane - kArrival * r;
  if (flow(frames, first, last) < kFlow * r) {
    v.why = str("no evidence: flat at ", where, ", but the fluid does not flow while there (at rest)");
    return v;
  }
  if (!arrived && !is_floor && !floor_is_wall) {
    v.why = str("no evidence: flat at ", where, " from the start while the fluid moves, but nothing holds the fluid "
                "up (no floor), so nothing pushes it against this side");
    return v;
  }
  v.wall = true;
  const int percent = int(std::lround(100.0f * v.share));
  v.why = arrived ? str("reached in frame ", frames[first]->frame, ", at it in ", percent, "% of the frames since")
                  : str("at it from frame ", frames[first]->frame, " in ", percent, "% of the frames while the fluid ",
                        is_floor ? "above it" : "on the floor", " flowed");
  return v;
}

}  // namespace

InferredContainer infer_container(const FluidSurvey& survey, float particle_radius, int up_axis) {
  InferredContainer c;
  const Aabb all = survey.bounds();
  std::vector<const FrameSurvey*> frames;
  for (const FrameSurvey& f : survey.frames)
    if (f.has_sheet()) frames.push_back(&f);
  if (frames.empty()) {
    c.summary = "no container inferred: no frame of the sequence holds 4 fluid particles or more";
    return c;
  }
  const int floor = 2 * up_axis, lid = 2 * up_axis + 1;
  // The floor first: whether the fluid is held up decides what its flat sides mean.
  std::array<int, 6> order{floor};
  for (int side = 0, k = 1; side < 6; ++side)
    if (side != floor) order[size_t(k++)] = side;
  for (int side : order) {
    const int axis = side / 2;
    const bool low = side % 2 == 0;
    c.plane[size_t(side)] = low ? all.min[axis] : all.max[axis];
    if (side == lid) continue;  // no lid
    const SideVerdict v = judge_side(frames, side, particle_radius, side == floor, c.wall[size_t(floor)]);
    c.pressed_share[size_t(side)] = v.share;
    c.why[size_t(side)] = v.why;
    if (!v.wall) continue;
    c.wall[size_t(side)] = true;
    // Particle centres stay about r off a wall.
    c.plane[size_t(side)] = low ? v.sheet - particle_radius : v.sheet + particle_radius;
  }
  std::string walls, open;
  for (int side = 0; side < 6; ++side) {
    if (side == lid || (side == floor && !c.wall[size_t(side)])) continue;
    const size_t s = size_t(side);
    if (c.wall[s])
      walls += str(walls.empty() ? "" : ", ", side_name(side), " at ", c.plane[s], " (", c.why[s], ")");
    else
      open += str(open.empty() ? "" : ", ", side_name(side), " (", c.why[s], ")");
  }
  if (!c.wall[size_t(floor)]) {
    c.summary = str("no container inferred: no floor (", side_name(floor), ": ", c.why[size_t(floor)], ")",
                    walls.empty() ? "" : str("; other sides: ", walls), open.empty() ? "" : str("; open: ", open));
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
  c.closed = std::count(c.wall.begin(), c.wall.end(), true) == 5;
  c.summary = str("container inferred from the fluid: walls ", walls, open.empty() ? "" : str("; open: ", open),
                  "; open top at ", tank.max[up_axis]);
  return c;
}

}  // namespace spume
