#pragma once
// The scene the render and diffuse studies run on: loaded as `spume run` loads it, with its fluid and
// diffuse caches simulated by the ordinary stages when missing or stale, and its busiest frame.
#include "render/app/scene/scene_args.h"
#include "render/app/report/study.h"

namespace spume::report {

// Loads context.scene_path (caches under context.out_root) and runs the simulation stages if needed.
SceneSetup load_report_scene(const StudyContext& context);

// The frame with the most diffuse particles, from OUT/<scene>/stats.csv (the diffuse stage's table).
int busiest_frame(const SceneSetup& setup);

}  // namespace spume::report
