#pragma once
// Reading a scene's solids (SI units). Each key is declared once, with its unit, default and range, in
// keys/scene_keys.h; the examples below are examples.
//
//   "solids": [
//     {"type": "tank", "min": [0, 0, 0], "max": [4, 3, 1], "open_top": true},   // m; hollow box
//     {"type": "box", "min": [..], "max": [..]},                                 // m; solid obstacle
//     {"type": "sphere", "center": [..], "radius": 0.2},                         // m
//     {"type": "box", "min": [..], "max": [..],                                  // a wave-maker piston
//      "motion": {"type": "sine", "axis": [1, 0, 0],  // direction (normalised here)
//                 "amplitude": 0.05,                  // m
//                 "frequency": 1.0,                   // Hz
//                 "phase": 0,                         // rad
//                 "start": 0}},                       // s; at rest before
//     {"type": "box", ..., "motion": {"type": "keyframes",
//                 "keys": [{"time": 0, "offset": [0, 0, 0]}, {"time": 2, "offset": [1, 0, 0]}]}},  // s, m
//     {"type": "box", "min": [..], "max": [..],                                  // a floating crate
//      "rotation": {"axis": [0, 0, 1], "angle": 0.3},    // optional, boxes only: about the box centre, rad
//      "dynamic": {"density": 500,                       // kg/m^3, or "mass": kg (exactly one of them)
//                  "friction": 0.5}},                    // Coulomb coefficient
//     {"type": "sphere", ..., "dynamic": {"mass": 2.0}},
//     {"type": "tank", "infer": true}   // file sources: the walls the fluid presses on (scene/container.h)
//   ]
// Motions translate the solid: offset(t) is added to its geometry (geometry/solids.h). A tank's "up" is
// the axis along which gravity is strongest. A "dynamic" box or sphere is a rigid body moved by
// gravity, the fluid's pressure and viscosity, and contacts (Bullet; fluid/rigid_bodies.h); it cannot
// also have a motion, and tanks cannot be dynamic. Only the built-in solver (fluid.source "solver")
// moves dynamic bodies.
#include "sim/core/params.h"
#include "sim/geometry/solids.h"

namespace spume {

// Reads root["solids"] (absent: no solids). Errors name the file and key path. A tank with "infer":
// true is not in the set: `infer_tank` says it was asked for.
SolidSet read_solids(const ParamReader& root, const Vec3f& gravity, bool& infer_tank);
// The same where no tank may be inferred (an "infer" entry is an error).
SolidSet read_solids(const ParamReader& root, const Vec3f& gravity);

}  // namespace spume
