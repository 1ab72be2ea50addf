#include "sim/scene/solids_reader.h"

#include <cmath>

#include "sim/core/error.h"
#include "sim/keys/scene_keys.h"

namespace spume {
namespace {

namespace k = keys::solids;

Motion read_motion(const ParamReader& m) {
  Motion motion;
  if (m.choice(k::motion_type) == "sine") {
    motion.kind = Motion::Kind::Sine;
    const Vec3f axis = m.vec3(k::motion_axis);
    if (!(axis.norm() > 0.0f)) m.fail_at("axis", "must be a non-zero direction [x, y, z]");
    motion.axis = axis.normalized();
    motion.amplitude = float(m.number(k::motion_amplitude));
    motion.frequency = float(m.number(k::motion_frequency));
    motion.phase = float(m.number(k::motion_phase));
    motion.start = m.number(k::motion_start);
  } else {
    motion.kind = Motion::Kind::Keyframes;
    const auto keyframes = m.array_of_objects("keys");
    if (keyframes.empty()) m.fail_at("keys", "missing: [{\"time\": s, \"offset\": [x, y, z] m}, ...], at least one");
    for (const ParamReader& key : keyframes) {
      const double t = key.number(k::keys_time);
      if (!motion.times.empty() && !(t > motion.times.back()))
        key.fail_at("time", str("keyframe times must increase; ", t, " follows ", motion.times.back()));
      motion.times.push_back(t);
      motion.offsets.push_back(key.vec3(k::keys_offset));
    }
  }
  return motion;
}

Quatf read_rotation(const ParamReader& r) {
  const Vec3f axis = r.vec3(k::rotation_axis);
  if (!(axis.norm() > 0.0f) || !finite(axis)) r.fail_at("axis", "must be a non-zero direction [x, y, z]");
  const double angle = r.number(k::rotation_angle);
  return Quatf(Eigen::AngleAxisf(float(angle), axis.normalized())).normalized();
}

Dynamics read_dynamics(const ParamReader& d) {
  Dynamics out;
  out.enabled = true;
  if (d.has("mass") == d.has("density"))
    d.fail_at("density", "give exactly one of \"density\" (kg/m^3) and \"mass\" (kg)");
  if (d.has("density")) out.density = float(d.number(k::density));
  if (d.has("mass")) out.mass = float(d.number(k::mass));
  out.friction = float(d.number(k::friction));
  return out;
}

}  // namespace

SolidSet read_solids(const ParamReader& root, const Vec3f& gravity, bool& infer_tank) {
  infer_tank = false;
  int up = 1;
  if (gravity.norm() > 0.0f) gravity.cwiseAbs().maxCoeff(&up);
  std::vector<Solid> solids;
  for (const ParamReader& r : root.array_of_objects("solids")) {
    Solid s;
    const std::string type = r.choice(k::type);
    if (type == "tank" && r.boolean(k::infer)) {
      for (const char* key : {"min", "max", "motion", "rotation", "dynamic"})
        if (r.has(key)) r.fail_at(key, "an inferred tank takes its walls from the fluid; give either \"infer\" or the geometry");
      if (infer_tank) r.fail_at("infer", "only one tank can be inferred");
      infer_tank = true;
      continue;
    }
    if (type != "tank" && r.has("infer")) r.fail_at("infer", "only a tank can be inferred");
    if (type == "sphere") {
      s.kind = Solid::Kind::Sphere;
      s.center = r.vec3(k::center);
      s.radius = float(r.number(k::radius));
    } else {
      s.kind = type == "tank" ? Solid::Kind::Tank : Solid::Kind::Box;
      s.min = r.vec3(k::min);
      s.max = r.vec3(k::max);
      if (!(s.min.array() < s.max.array()).all()) r.fail_at("max", "must be above min on every axis");
      if (s.kind == Solid::Kind::Tank) {
        s.open_top = r.boolean(k::open_top);
        s.up_axis = up;
      }
    }
    if (r.has("rotation")) {
      if (s.kind != Solid::Kind::Box) r.fail_at("rotation", "only boxes can be rotated");
      s.orientation = read_rotation(r.child("rotation"));
    }
    if (r.has("motion")) s.motion = read_motion(r.child("motion"));
    with_context(r.source() + ": " + r.path_of("motion"), [&] { s.motion.validate("motion"); });
    if (r.has("dynamic")) {
      if (s.kind == Solid::Kind::Tank) r.fail_at("dynamic", "a tank cannot be dynamic (only boxes and spheres)");
      if (r.has("motion")) r.fail_at("dynamic", "a solid has either a \"motion\" or \"dynamic\", not both");
      s.dynamics = read_dynamics(r.child("dynamic"));
    }
    solids.push_back(std::move(s));
  }
  SolidSet set(std::move(solids));
  with_context(root.source() + ": " + root.path_of("solids"), [&] { set.validate(); });
  return set;
}

SolidSet read_solids(const ParamReader& root, const Vec3f& gravity) {
  bool infer = false;
  SolidSet set = read_solids(root, gravity, infer);
  if (infer) root.fail_at("solids", "a tank inferred from the fluid (\"infer\": true) needs fluid files (fluid.source \"files\")");
  return set;
}

}  // namespace spume
