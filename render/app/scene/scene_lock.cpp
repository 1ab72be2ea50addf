#include "render/app/scene/scene_lock.h"

#include <cstdio>

#include "sim/core/atomic_file.h"
#include "sim/io/stage_record.h"
#include "sim/stage/simulate_scene.h"

namespace spume {

std::unique_ptr<OutputLock> lock_scene_output(const SceneSetup& setup, OutputLock::Mode mode, const std::string& what) {
  const std::filesystem::path scene_out = setup.out_root / setup.sim.name;
  // Inputs that cannot be read at all are named before anything is created in the output folder.
  if (setup.sim.source == FluidSourceKind::Files) scene_fluid_source(setup.sim, setup.out_root);
  // Renders share only with renders that would write the same frames.
  const std::string keys = record_digest({{"render", setup.render_keys}, {"simulation", setup.sim.diffuse_keys}});
  auto lock = std::make_unique<OutputLock>(scene_out, mode, keys, what, setup.quiet);
  const std::filesystem::path frames_dir = (scene_out / setup.render.frame_pattern).parent_path();
  int removed = 0;
  for (const auto& dir : {scene_out, scene_out / "fluid", scene_out / "diffuse", scene_out / "fluid_bgeo",
                          scene_out / "diffuse_bgeo", scene_out / "lookdev", frames_dir})
    removed += remove_dead_temporaries(dir);
  if (removed > 0 && !setup.quiet)
    std::fprintf(stderr, "removed %d temporary files left in %s by runs that were killed\n", removed,
                 scene_out.string().c_str());
  return lock;
}

}  // namespace spume
