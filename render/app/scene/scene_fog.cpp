#include "render/app/scene/scene_fog.h"

#include "render/stage/fog_export.h"
#include "sim/core/error.h"
#include "sim/io/cache_layout.h"
#include "sim/stage/stage_exports.h"

namespace spume {

void check_fog_request(const SceneSetup& setup) {
  if (setup.sim.fog_voxel > 0.0f && !setup.render.draws_diffuse())
    fail("output.fog: ", setup.sim.fog_voxel, " asks for fog volumes of the diffuse material, but no type is drawn "
         "(render.spray.radius, render.foam.radius and render.bubble.radius are all 0)");
}

void bring_fog_in_line(const SceneSetup& setup) {
  // The look is the render's radii and absorption, which the scene's render keys fix.
  const std::filesystem::path scene_out = setup.out_root / setup.sim.name;
  bring_export_in_line(fog_export(setup.render, setup.sim.fog_voxel, scene_out),
                       recorded_frames(diffuse_cache_path(scene_out, 0).parent_path(), {}), scene_out, setup.quiet);
}

}  // namespace spume
