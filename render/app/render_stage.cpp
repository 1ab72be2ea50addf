#include "render_stage.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/frame_spec.h"
#include "core/progress.h"
#include "image/png_io.h"
#include "io/frame_pattern.h"
#include "io/spume_cache.h"
#include "pipeline/body_track_file.h"
#include "pipeline/cache_state.h"
#include "pipeline/frame_renderer.h"
#include "pipeline/simulate_run.h"
#include "pipeline/simulate_scene.h"
#include "solid_meshes.h"

namespace spume {
namespace {

bool valid_frame_on_disk(const std::filesystem::path& path, const RenderSettings& s) {
  if (!std::filesystem::is_regular_file(path)) return false;
  try {
    const ImageRGB8 image = read_png(path);
    return image.width == s.width && image.height == s.height;
  } catch (const Error&) {
    return false;
  }
}

// Bounds of what the camera should see when the scene sets no camera: the tanks and the fluid.
Aabb scene_bounds(const SimScene& scene, const FluidFrame& first) {
  Aabb box;
  for (const Solid& s : scene.solids.solids())
    if (s.kind == Solid::Kind::Tank) box.extend(Aabb{s.min, s.max});
  for (const Vec3f& p : first.positions) box.extend(p);
  return box;
}

float lowest_point(const SimScene& scene, const FluidFrame& first, int up) {
  Aabb box = scene_bounds(scene, first);
  for (const Solid& s : scene.solids.solids())
    box.extend(s.kind == Solid::Kind::Sphere ? Aabb{s.center - Vec3f::Constant(s.radius),
                                                    s.center + Vec3f::Constant(s.radius)}
                                             : Aabb{s.min, s.max});
  const float extent = (box.max - box.min).norm();
  return box.min[up] - 1e-3f * extent;
}

void remove_pattern_frames(const std::string& pattern) {
  std::error_code ec;
  for (int f : find_pattern_frames(pattern)) std::filesystem::remove(expand_frame_pattern(pattern, f), ec);
}

}  // namespace

std::filesystem::path reset_stale_frames(const std::string& pattern, const std::string& render_fingerprint) {
  const std::filesystem::path frames_dir = std::filesystem::path(expand_frame_pattern(pattern, 0)).parent_path();
  if (!cache_is_current(frames_dir, render_fingerprint, {})) {
    if (std::filesystem::is_directory(frames_dir)) remove_pattern_frames(pattern);
    mark_cache_complete(frames_dir, render_fingerprint);
  }
  return frames_dir;
}

PreparedRender prepare_render(const SimScene& scene, RenderSettings settings, const std::filesystem::path& out_root) {
  const Vec3f up = -scene.gravity.normalized();
  if (!(up.dot(Vec3f::UnitY()) > 0.999f))
    fail(scene.name, ": /gravity: the renderer's sky and ground assume +y is up; gravity must point along -y");
  PreparedRender p;
  p.scene = &scene;
  p.scene_out = out_root / scene.name;
  if (scene.source == FluidSourceKind::Solver &&
      !cache_is_current(p.scene_out / "fluid", scene.fluid_fingerprint, {}))
    fail((p.scene_out / "fluid").string(), ": no current fluid caches for this scene (missing, unfinished or made "
         "with other fluid keys); run `spume simulate` or `spume run` first");
  p.source = scene_fluid_source(scene, out_root);
  p.frames = diffuse_frames_to_run(scene, *p.source, SimulateOptions{});
  if (settings.draw_solids) p.bodies = scene_body_track(scene, p.scene_out);

  const FluidFrame first = p.source->load(p.frames.front());
  if (settings.camera.empty())
    settings.camera.push_back(auto_camera(scene_bounds(scene, first), up, 40.0f,
                                          float(settings.width) / float(settings.height)));
  settings.camera_up = up;
  settings.environment.ground_height = settings.ground_height.value_or(lowest_point(scene, first, 1));
  p.settings = std::move(settings);
  return p;
}

FrameInputs LoadedFrame::inputs() const {
  FrameInputs in;
  in.index = index;
  in.time = time;
  in.fluid = fluid.positions;
  in.diffuse = has_diffuse ? &diffuse : nullptr;
  in.solids = solids;
  return in;
}

LoadedFrame load_frame(PreparedRender& p, int f) {
  return with_context(str("frame ", f), [&] {
    LoadedFrame frame;
    frame.index = f;
    frame.time = double(f) / p.scene->fluid.fps;
    if (p.settings.draw_surface) frame.fluid = p.source->load(f);
    if (p.settings.draws_diffuse()) {
      const auto cache = diffuse_cache_path(p.scene_out, f);
      if (!std::filesystem::is_regular_file(cache))
        fail(cache.string(), ": no diffuse cache for this frame; run `spume simulate` (or `spume run`) first");
      frame.diffuse = read_diffuse_cache(cache);
      frame.has_diffuse = true;
    }
    if (p.settings.draw_solids) {
      Camera camera = camera_at(p.settings.camera, frame.time, p.settings.width, p.settings.height);
      frame.solids = solid_meshes(solids_at_time(p.scene->solids, p.bodies, frame.time), camera.position);
    }
    return frame;
  });
}

RenderStageSummary run_render_stage(const SimScene& scene, RenderSettings settings_in,
                                    const std::string& render_fingerprint, const RenderStageOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  PreparedRender prepared = prepare_render(scene, std::move(settings_in), options.out_root);
  const RenderSettings& settings = prepared.settings;
  const std::string pattern = (prepared.scene_out / settings.frame_pattern).string();
  const std::vector<int>& available = prepared.frames;
  std::vector<int> frames = available;
  if (options.frame_spec) {
    frames.clear();
    for (int f : parse_frame_spec(*options.frame_spec, available.front(), available.back(), "--frames"))
      if (std::binary_search(available.begin(), available.end(), f)) frames.push_back(f);
  }
  RenderStageSummary summary;
  if (frames.empty()) return summary;

  const std::filesystem::path frames_dir = reset_stale_frames(pattern, render_fingerprint);

  FrameRenderer renderer(settings);
  Progress progress("render " + scene.name, frames.size(), options.quiet);
  bool any_reconstructed = false, any_gl = false, any_volume = false;
  FrameReport total;  // stage seconds summed over the written frames
  for (size_t k = 0; k < frames.size(); ++k) {
    const int f = frames[k];
    const std::filesystem::path path = expand_frame_pattern(pattern, f);
    if (summary.first_frame.empty()) summary.first_frame = path, summary.first_frame_number = f;
    if (!options.overwrite && valid_frame_on_disk(path, settings)) {
      ++summary.skipped;
      progress.update(k + 1, "exists, skipped");
      continue;
    }
    const LoadedFrame frame = load_frame(prepared, f);  // its errors name the frame
    with_context(str("frame ", f), [&] {
      FrameReport report;
      const ImageRGB8 image = renderer.render(frame.inputs(), &report);
      write_png(path, image);
      any_reconstructed |= report.reconstructed;
      any_gl |= report.used_gl;
      any_volume |= report.volume;
      total.reconstruct_seconds += report.reconstruct_seconds;
      total.surface_seconds += report.surface_seconds;
      total.volume_seconds += report.volume_seconds;
      ++summary.written;
      if (!options.quiet) std::printf("Saved: %s\n", path.string().c_str()), std::fflush(stdout);
      progress.update(k + 1, str(report.triangles, " triangles, ", report.spheres, " diffuse spheres"));
    });
  }
  const auto per_frame = [&](double seconds) {
    return str(" (", int(std::lround(1e3 * seconds / std::max(summary.written, 1))), " ms per frame)");
  };
  if (any_reconstructed) summary.stages.push_back("surface reconstruction" + per_frame(total.reconstruct_seconds));
  if (any_gl) summary.stages.push_back("OSMesa surface pass" + per_frame(total.surface_seconds));
  if (!any_gl && summary.written > 0) summary.stages.push_back("CPU sky and ground (nothing showed a surface)");
  if (any_volume)
    summary.stages.push_back((settings.volume.integrator == VolumeIntegrator::Exact ? "volume pass (exact)"
                                                                                    : "volume pass (march)") +
                             per_frame(total.volume_seconds));
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress.finish(str(summary.written, " written, ", summary.skipped, " skipped -> ", frames_dir.string()));
  return summary;
}

}  // namespace spume
