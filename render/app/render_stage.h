#pragma once
// The render stage of a run: per frame, the fluid frame (for the surface), the diffuse cache, the
// solids at the frame's time -> OUT/<scene>/<render.frames pattern>, 8-bit sRGB PNG written
// atomically. It reads caches only and never simulates.
//
// Resuming: the frames folder records the render fingerprint (the scene's diffuse fingerprint and
// every render key). When it matches, frames already on disk that decode at the right size are
// skipped (unless overwrite); when it differs, the old frames of the pattern are deleted first, so a
// folder never mixes frames of different settings.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/frame_renderer.h"
#include "pipeline/render_settings.h"
#include "scene/body_track.h"
#include "scene/fluid_source.h"
#include "scene/sim_scene.h"

namespace spume {

struct RenderStageOptions {
  std::filesystem::path out_root = "out";
  // Render only these: "7", "0-99", "0-99:2", "1-3,5,10-20" (core/frame_spec.h), clamped to the
  // scene's frames, so a farm chunk that overshoots the end renders what exists.
  std::optional<std::string> frame_spec;
  bool overwrite = false;
  bool quiet = false;
};

struct RenderStageSummary {
  int written = 0, skipped = 0;
  double seconds = 0.0;
  std::vector<std::string> stages;  // what ran, e.g. "surface reconstruction", "OSMesa surface pass"
  std::filesystem::path first_frame;  // the first frame written or found
  int first_frame_number = -1;
};

// A scene ready to render from its caches: the fluid source, the frames it has, and the settings
// with the camera framed and the ground placed (from the sequence's first frame, so every farm chunk
// agrees). Throws when a solver scene has no current fluid caches.
struct PreparedRender {
  const SimScene* scene = nullptr;
  RenderSettings settings;
  std::filesystem::path scene_out;  // OUT/<scene>
  std::unique_ptr<FluidSource> source;
  std::vector<int> frames;          // available, sorted
  BodyTrack bodies;                 // the dynamic solids' poses (scenes with dynamic solids)
};
PreparedRender prepare_render(const SimScene& scene, RenderSettings settings, const std::filesystem::path& out_root);

// The inputs of one frame, read from the caches (fluid only when the surface is drawn, diffuse only
// when a type is drawn; a missing diffuse cache is an error naming it).
struct LoadedFrame {
  FluidFrame fluid;
  DiffuseFrame diffuse;
  bool has_diffuse = false;
  std::vector<SolidMesh> solids;
  int index = 0;
  double time = 0.0;
  FrameInputs inputs() const;  // views into this object
};
LoadedFrame load_frame(PreparedRender& prepared, int frame);

// The resume rule above on its own: when the frames folder of `pattern` records another fingerprint,
// its frames are deleted and the new fingerprint recorded. Returns the folder. Farms call it once
// before their tasks start, so no task deletes a frame another task has just written.
std::filesystem::path reset_stale_frames(const std::string& pattern, const std::string& render_fingerprint);

RenderStageSummary run_render_stage(const SimScene& scene, RenderSettings settings,
                                    const std::string& render_fingerprint, const RenderStageOptions& options);

}  // namespace spume
