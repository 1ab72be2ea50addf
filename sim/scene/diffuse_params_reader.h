#pragma once
#include "sim/core/frames.h"
#include "sim/core/params.h"
#include "sim/diffuse/params.h"

namespace spume {

// Reads the `diffuse` object of a scene, as declared in keys/diffuse_keys.h: SI units; a key that is
// absent takes its declared default, carried to the scene's radius by Froude similarity, so a scene
// built at another scale emits alike; a key that is present is taken literally. `gravity` is the
// scene's, m/s^2.
DiffuseParams read_diffuse_params(const ParamReader& diffuse, const FluidSequenceInfo& fluid, const Vec3f& gravity);

// Every parameter a run used (SI), by its key, written next to the outputs so a run can be reproduced.
Json diffuse_params_to_json(const DiffuseParams& p);

}  // namespace spume
