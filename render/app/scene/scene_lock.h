#pragma once
// Taking a scene's output folder for one run (core/output_lock.h) and clearing what killed writers
// left there (core/atomic_file.h).
#include <memory>

#include "sim/core/output_lock.h"
#include "render/app/scene/scene_args.h"

namespace spume {

// Simulations take the folder alone; renders share it with renders of the same keys. Once granted,
// the temporary files of dead writers on this host are removed from the scene's folders.
std::unique_ptr<OutputLock> lock_scene_output(const SceneSetup& setup, OutputLock::Mode mode, const std::string& what);

}  // namespace spume
