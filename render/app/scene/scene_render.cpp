#include "render/app/scene/scene_render.h"

#include <cstdio>

#include "sim/core/error.h"
#include "sim/core/messages.h"
#include "sim/io/cache_layout.h"
#include "sim/stage/body_track_file.h"
#include "sim/stage/fluid_stage.h"
#include "sim/stage/diffuse_stage.h"
#include "sim/stage/simulate_scene.h"

namespace spume {

SceneRender scene_render(const SimScene& scene, const std::filesystem::path& out_root) {
  SceneRender r;
  RenderScene& s = r.scene;
  s.name = scene.name;
  s.scene_out = out_root / scene.name;
  s.fps = scene.fluid.fps;
  s.up = -scene.gravity.normalized();
  s.gravity = scene.gravity;
  if (scene.source == FluidSourceKind::Solver) {
    const std::optional<StageRecord> made = read_stage_record(s.scene_out / "fluid");
    const RecordMatch match = fluid_caches_match(scene, out_root, made ? made->last_frame : 0);
    if (!made || match.kind != RecordMatch::Kind::Current)
      fail((s.scene_out / "fluid").string(), ": the fluid caches are not current for this scene (", match.why,
           "); run `spume simulate` or `spume run` first");
  }
  s.fluid = scene_fluid_source(scene, out_root);
  s.frames = diffuse_frames_to_run(scene, *s.fluid, DiffuseStageOptions{});
  s.bodies = scene_body_track(scene, s.scene_out);
  r.inputs = read_scene_inputs(scene, out_root, true);
  s.fluid_pattern = r.inputs.survey.pattern;
  s.solids = r.inputs.solids;
  s.fluid_bounds = r.inputs.survey.bounds();
  std::vector<int> surveyed;
  for (const FrameSurvey& f : r.inputs.survey.frames) surveyed.push_back(f.frame);
  s.sequence_digest = record_digest(diffuse_stage_record(scene, r.inputs, surveyed, s.scene_out).to_json());
  return r;
}

void print_input_warnings(const SceneRender& render) {
  for (const std::string& note : render.inputs.notes)
    if (messages::is_warning(note)) messages::warning(note);
}

void check_diffuse_caches(const SimScene& scene, const SceneRender& render, const RenderSettings& settings,
                          const std::vector<int>& frames) {
  if (!settings.draws_diffuse() || frames.empty()) return;
  const std::filesystem::path dir = render.scene.scene_out / "diffuse";
  const std::optional<StageRecord> made = read_stage_record(dir);
  if (!made)
    fail(dir.string(), ": no finished diffuse caches (never simulated, or a simulation was interrupted); run "
         "`spume simulate` or `spume run` first");
  // The caches may start later than the scene (simulate --frames A-B); they must reach every frame.
  std::vector<int> range;
  for (int f : render.scene.frames)
    if (f >= made->first_frame && f <= frames.back()) range.push_back(f);
  if (frames.front() < made->first_frame || range.empty())
    fail(dir.string(), ": the diffuse caches start at frame ", made->first_frame, ", after frame ", frames.front(),
         "; run `spume simulate` for the frames to render");
  // Only the caches of the frames drawn must be on disk: earlier ones may have been removed for room.
  const RecordMatch match = diffuse_caches_match(scene, render.inputs, range, render.scene.scene_out, frames);
  if (match.kind == RecordMatch::Kind::Prefix)
    fail(dir.string(), ": the diffuse caches end at frame ", made->last_frame, ", before frame ", frames.back(),
         "; run `spume simulate` (or `spume run`) for the frames to render");
  if (match.kind == RecordMatch::Kind::Stale)
    fail(dir.string(), ": the diffuse caches are not current for this scene: ", match.why,
         "; run `spume simulate` (or `spume run`) first");
  repeat_warnings(made);
}

}  // namespace spume
