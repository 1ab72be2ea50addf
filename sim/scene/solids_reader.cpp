#include "solids_reader.h"

#include <cmath>

#include "core/error.h"

namespace spume {
namespace {

Vec3f required_vec3(const ParamReader& r, const std::string& key, const char* what) {
  const auto v = r.optional_vec3(key);
  if (!v) r.fail_at(key, str("missing: ", what));
  return *v;
}

Motion read_motion(const ParamReader& m) {
  const Motion defaults;
  Motion motion;
  const std::string type = m.choice("type", "sine", {"sine", "keyframes"});
  if (type == "sine") {
    motion.kind = Motion::Kind::Sine;
    const Vec3f axis = m.vec3("axis", defaults.axis);
    if (!(axis.norm() > 0.0f)) m.fail_at("axis", "must be a non-zero direction [x, y, z]");
    motion.axis = axis.normalized();
    motion.amplitude = float(m.number_in("amplitude", defaults.amplitude, 0.0, 1e3));
    motion.frequency = float(m.number_in("frequency", defaults.frequency, 0.0, 1e3));
    motion.phase = float(m.number("phase", defaults.phase));
    motion.start = m.number_in("start", defaults.start, 0.0, 1e6);
  } else {
    motion.kind = Motion::Kind::Keyframes;
    const auto keys = m.array_of_objects("keys");
    if (keys.empty()) m.fail_at("keys", "missing: [{\"time\": s, \"offset\": [x, y, z] m}, ...], at least one");
    for (const ParamReader& k : keys) {
      if (!k.has("time")) k.fail_at("time", "missing: the keyframe's time in s");
      const double t = k.number("time", 0.0);
      if (!motion.times.empty() && !(t > motion.times.back()))
        k.fail_at("time", str("keyframe times must increase; ", t, " follows ", motion.times.back()));
      motion.times.push_back(t);
      motion.offsets.push_back(required_vec3(k, "offset", "the keyframe's offset [x, y, z] in m"));
    }
  }
  return motion;
}

Quatf read_rotation(const ParamReader& r) {
  const Vec3f axis = required_vec3(r, "axis", "the rotation axis [x, y, z]");
  if (!(axis.norm() > 0.0f) || !finite(axis)) r.fail_at("axis", "must be a non-zero direction [x, y, z]");
  if (!r.has("angle")) r.fail_at("angle", "missing: the rotation angle in rad");
  const double angle = r.number_in("angle", 0.0, -1e3, 1e3);
  return Quatf(Eigen::AngleAxisf(float(angle), axis.normalized())).normalized();
}

Dynamics read_dynamics(const ParamReader& d) {
  const Dynamics defaults;
  Dynamics out;
  out.enabled = true;
  if (d.has("mass") == d.has("density"))
    d.fail_at("density", "give exactly one of \"density\" (kg/m^3) and \"mass\" (kg)");
  if (d.has("density")) out.density = float(d.positive("density", defaults.density));
  if (d.has("mass")) out.mass = float(d.positive("mass", defaults.mass));
  out.friction = float(d.number_in("friction", defaults.friction, 0.0, 100.0));
  return out;
}

}  // namespace

SolidSet read_solids(const ParamReader& root, const Vec3f& gravity, bool& infer_tank) {
  infer_tank = false;
  int up = 1;
  if (gravity.norm() > 0.0f) gravity.cwiseAbs().maxCoeff(&up);
  std::vector<Solid> solids;
  for (const ParamReader& r : root.array_of_objects("solids")) {
    const Solid defaults;
    Solid s;
    const std::string type = r.choice("type", "tank", {"tank", "box", "sphere"});
    if (type == "tank" && r.boolean("infer", false)) {
      for (const char* key : {"min", "max", "motion", "rotation", "dynamic"})
        if (r.has(key)) r.fail_at(key, "an inferred tank takes its walls from the fluid; give either \"infer\" or the geometry");
      if (infer_tank) r.fail_at("infer", "only one tank can be inferred");
      infer_tank = true;
      continue;
    }
    if (type != "tank" && r.has("infer")) r.fail_at("infer", "only a tank can be inferred");
    if (type == "sphere") {
      s.kind = Solid::Kind::Sphere;
      s.center = required_vec3(r, "center", "the sphere's centre [x, y, z] in m");
      if (!r.has("radius")) r.fail_at("radius", "missing: the sphere's radius in m");
      s.radius = float(r.positive("radius", defaults.radius));
    } else {
      s.kind = type == "tank" ? Solid::Kind::Tank : Solid::Kind::Box;
      s.min = required_vec3(r, "min", "the lower corner [x, y, z] in m");
      s.max = required_vec3(r, "max", "the upper corner [x, y, z] in m");
      if (!(s.min.array() < s.max.array()).all()) r.fail_at("max", "must be above min on every axis");
      if (s.kind == Solid::Kind::Tank) {
        s.open_top = r.boolean("open_top", defaults.open_top);
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
