#pragma once
// The render stage of a run: per frame, the fluid frame (for the surface), the diffuse cache, the
// solids at the frame's time -> OUT/<scene>/<render.frames pattern>, 8-bit sRGB PNG written
// atomically. It reads caches only and never simulates.
//
// Frames know their sources: each PNG records (in a text chunk, written atomically with the pixels)
// the render keys, a digest of the whole sequence's inputs and simulation keys, and the identity of
// the diffuse cache and fluid file it was drawn from. A frame on disk is skipped only when its record
// equals what this render would write (unless overwrite); frames outside the render's selection are
// never touched, and the summary counts those that are stale. The stage refuses caches that are not
// current for the scene (missing, unfinished, or made from other keys or inputs), naming why.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/frame_renderer.h"
#include "pipeline/render_settings.h"
#include "pipeline/scene_inputs.h"
#include "geometry/body_track.h"
#include "io/fluid_source.h"
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
  int stale_elsewhere = 0;  // frames on disk outside the selection that do not match the scene now
  double seconds = 0.0;
  std::vector<std::string> stages;  // what ran, e.g. "surface reconstruction", "OSMesa surface pass"
  std::filesystem::path first_frame;  // the first frame written or found
  int first_frame_number = -1;
};

// A scene ready to render from its caches: the fluid source, the frames it has, and the settings
// with the camera framed and the ground placed (from the whole sequence's bounds, so every farm chunk
// agrees). Throws when a solver scene has no current fluid caches.
struct PreparedRender {
  const SimScene* scene = nullptr;
  RenderSettings settings;
  std::filesystem::path scene_out;  // OUT/<scene>
  std::unique_ptr<FluidSource> source;
  std::vector<int> frames;          // available, sorted
  BodyTrack bodies;                 // the dynamic solids' poses (scenes with dynamic solids)
  SolidSet solids;                  // the scene's, with an inferred tank (pipeline/scene_inputs.h)
  SceneInputs inputs;               // the survey of the whole sequence, the domain
  std::string sequence_digest;      // of the simulation keys and every input file (frame records)
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

// Throws unless the diffuse caches (when the settings draw diffuse material) are finished, current
// for the scene and hold `frames` (sorted).
void check_diffuse_caches(const PreparedRender& prepared, const std::vector<int>& frames);

// What frame `frame` is drawn from, as stored in its PNG (compact JSON).
std::string frame_record(const PreparedRender& prepared, const nlohmann::json& render_keys, int frame);

// `render_keys`: the scene's "render" object as written (part of each frame's record).
RenderStageSummary run_render_stage(const SimScene& scene, RenderSettings settings, const nlohmann::json& render_keys,
                                    const RenderStageOptions& options);

}  // namespace spume
