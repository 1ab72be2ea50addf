#pragma once
// The render stage: per frame, the fluid (for the surface), the diffuse cache, the solids at the
// frame's time -> OUT/<scene>/<render.frames pattern>, 8-bit sRGB PNG written atomically. It reads
// caches only and never simulates; the caller has checked that they are current.
//
// Frames know their sources: each PNG records (in a text chunk, written atomically with the pixels)
// the render keys, what they resolved to (camera, ground), the renderer's generation, the sequence's
// digest, and the identity of the diffuse cache and fluid file it was drawn from. A frame on disk is
// skipped only when its record equals what this render would write (unless overwrite); frames outside
// the render's selection are never touched, and the summary counts those that are stale.
//
// With render.exr, each frame's layers also go to an OpenEXR file beside its PNG (frame_exr.h) with the
// same record, and a frame is current only when both are. With it off, EXR frames of earlier runs are
// removed (all of them: none can be current), and the log says so.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "render/frame/frame_renderer.h"
#include "render/frame/render_settings.h"
#include "render/stage/render_scene.h"
#include "sim/core/memory_room.h"

namespace spume {

struct RenderStageOptions {
  bool overwrite = false;
  bool quiet = false;
};

struct RenderStageSummary {
  int written = 0, skipped = 0;
  int stale_elsewhere = 0;  // frames on disk outside the selection that do not match the scene now
  int exr_removed = 0;      // EXR frames of an earlier run, removed because render.exr is off
  double seconds = 0.0;
  std::vector<std::string> stages;  // what ran, e.g. "surface reconstruction", "OSMesa surface pass"
  std::filesystem::path first_frame;  // the first frame written or found
  int first_frame_number = -1;
};

// What the render holds a diffuse particle at its peak (the frame drawn and the one loaded ahead, the
// volume pass's bins): 52 bytes over the whole process rendering the lighthouse's 95.7M frames at
// 1920x1080 (tests/bench/RESULTS.md, "Memory a diffuse particle"), rounded up.
constexpr double kRenderBytesPerDiffuseParticle = 60.0;

// A scene ready to render: the settings with the camera framed and the ground placed from the
// whole sequence's bounds, so every farm chunk agrees.
struct PreparedRender {
  RenderScene* scene = nullptr;
  RenderSettings settings;
  std::shared_ptr<MemoryRoom> diffuse_room;  // refuses a diffuse cache that cannot fit
};
PreparedRender prepare_render(RenderScene& scene, RenderSettings settings);

// The scene's frames a frame spec selects ("7", "0-99", "0-99:2", "1-3,5,10-20"; core/frame_spec.h),
// clamped to those there are, so a farm chunk that overshoots the end renders what exists. No spec:
// every frame.
std::vector<int> frames_to_render(const RenderScene& scene, const std::optional<std::string>& spec);

// The inputs of one frame, read from the caches (fluid only when the surface is drawn, diffuse only
// when a type is drawn; a missing diffuse cache is an error naming it).
struct LoadedFrame {
  FluidFrame fluid;
  DiffusePoints diffuse;  // positions and types only: what the renderer draws
  std::vector<Vec3f> diffuse_velocities;  // m/s, with motion blur only
  bool has_diffuse = false;
  std::vector<SolidMesh> solids;
  SolidSet solid_set;  // the solids at the frame's time, with their velocities (motion vectors)
  int index = 0;
  double time = 0.0;
  FrameInputs inputs() const;  // views into this object
};
LoadedFrame load_frame(PreparedRender& prepared, int frame);

// What frame `frame` is drawn from, as stored in its PNG (compact JSON).
std::string frame_record(const PreparedRender& prepared, const nlohmann::json& render_keys, int frame);

// Renders `frames` (a selection of the scene's, sorted). `render_keys`: the scene's "render" object as
// written (part of each frame's record).
RenderStageSummary run_render_stage(PreparedRender& prepared, const nlohmann::json& render_keys,
                                    const std::vector<int>& frames, const RenderStageOptions& options);

}  // namespace spume
