#pragma once
// From a simulation scene to what the render stage needs (stage/render_scene.h), and the check that
// the caches it will read are current: the spume command's bridge between the two halves, so that the
// render stage itself knows nothing of how scenes are simulated.
#include <filesystem>
#include <vector>

#include "render/frame/render_settings.h"
#include "sim/stage/scene_inputs.h"
#include "sim/scene/sim_scene.h"
#include "render/stage/render_scene.h"

namespace spume {

struct SceneRender {
  SceneInputs inputs;  // the survey of the whole sequence, the solids as resolved, the domain
  RenderScene scene;
};

// Throws when a solver scene has no current fluid caches (naming why).
SceneRender scene_render(const SimScene& scene, const std::filesystem::path& out_root);

// Prints the warnings among the inputs' notes (a radius that does not fit the particles' spacing) to
// stderr, even under --quiet: a render drawn from doubtful inputs says so, as the simulation did.
void print_input_warnings(const SceneRender& render);

// Throws unless the diffuse caches (when the settings draw diffuse material) are finished, current
// for the scene and hold `frames` (sorted), naming the first difference. Says the warnings given
// while the caches were made again: they hold for the pictures drawn from them.
void check_diffuse_caches(const SimScene& scene, const SceneRender& render, const RenderSettings& settings,
                          const std::vector<int>& frames);

}  // namespace spume
