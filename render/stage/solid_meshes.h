#pragma once
// The scene's solids as triangle meshes for one frame, in world space. A tank is drawn as a cutaway:
// only the walls the camera sees from inside (the camera on the inner side of the wall's plane) and
// the floor, so the walls between the camera and the water never hide it -- neither in the OSMesa
// pass nor as opaque blockers of the volume pass.
#include <vector>

#include "render/frame/frame_renderer.h"
#include "sim/geometry/solids.h"

namespace spume {

// `solids` at the frame's time (SolidSet::at_time), seen from `eye`, lit from `sun_direction`
// (towards the sun: which walls a tank's shadow caster thickens).
std::vector<SolidMesh> solid_meshes(const SolidSet& solids, const Vec3f& eye, const Vec3f& sun_direction);

}  // namespace spume
