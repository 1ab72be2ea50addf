#pragma once
#include "core/frames.h"
#include "core/params.h"
#include "diffuse/params.h"

namespace spume {

// Reference particle radius of the default parameters below, m.
constexpr float kDefaultsReferenceRadius = 0.02f;

// Reads the `diffuse` object of a scene. Every key is in SI units. A key that is absent takes its
// default, stated for a fluid of radius kDefaultsReferenceRadius and carried to the scene's radius
// by Froude similarity (lengths x s, velocities and times x sqrt(s), rates / sqrt(s), energies x
// mass ratio x s), so a scene built at another scale emits alike. A key that is present is taken
// literally. `gravity` is the scene's, m/s^2.
DiffuseParams read_diffuse_params(const ParamReader& diffuse, const FluidSequenceInfo& fluid, const Vec3f& gravity);

// The resolved parameters as JSON (SI), written next to the outputs so a run can be reproduced.
Json diffuse_params_to_json(const DiffuseParams& p);

}  // namespace spume
