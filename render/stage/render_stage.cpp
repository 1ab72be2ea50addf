#include "render/stage/render_stage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sim/core/error.h"
#include "sim/core/out_of_memory.h"
#include "sim/core/frame_spec.h"
#include "sim/core/parallel.h"
#include "sim/core/progress.h"
#include "sim/core/stopwatch.h"
#include "render/frame/frame_exr.h"
#include "render/image/png_io.h"
#include "sim/core/messages.h"
#include "sim/io/cache_layout.h"
#include "sim/io/file_identity.h"
#include "sim/io/frame_pattern.h"
#include "sim/io/spume_cache.h"
#include "render/stage/frame_prefetch.h"
#include "render/stage/png_writer_thread.h"
#include "render/stage/render_stats.h"
#include "render/stage/solid_meshes.h"

namespace spume {
namespace {

// Bump when spume's pictures change for the same keys and caches (frames on disk are then stale).
constexpr int kRenderGeneration = 2;

// Bounds of what the camera should see when the scene sets no camera: the tanks and the fluid over
// the whole sequence (a dam break stays in the picture from its first frame to its last).
Aabb scene_bounds(const RenderScene& scene) {
  const Aabb& fluid = scene.fluid_bounds;
  Aabb box = fluid;
  for (const Solid& s : scene.solids.solids())
    if (s.kind == Solid::Kind::Tank) {
      // A tank far taller than the water would shrink the water to a strip: its height counts only
      // up to where the fluid ever reaches.
      Aabb tank{s.min, s.max};
      if (!fluid.empty())
        tank.max[s.up_axis] = std::max(std::min(s.max[s.up_axis], fluid.max[s.up_axis]), s.min[s.up_axis]);
      box.extend(tank);
    }
  return box;
}

float lowest_point(const RenderScene& scene, int up) {
  Aabb box = scene_bounds(scene);
  for (const Solid& s : scene.solids.solids())
    box.extend(s.kind == Solid::Kind::Sphere ? Aabb{s.center - Vec3f::Constant(s.radius),
                                                    s.center + Vec3f::Constant(s.radius)}
                                             : Aabb{s.min, s.max});
  const float extent = (box.max - box.min).norm();
  return box.min[up] - 1e-3f * extent;
}

void add_surface_stages(SurfacePassStats& sum, const SurfacePassStats& s) {
  sum.seconds_context += s.seconds_context, sum.seconds_upload += s.seconds_upload;
  sum.seconds_shadow += s.seconds_shadow, sum.seconds_opaque += s.seconds_opaque;
  sum.seconds_water_back += s.seconds_water_back, sum.seconds_water_front += s.seconds_water_front;
  sum.seconds_resolve += s.seconds_resolve, sum.seconds_readback += s.seconds_readback;
}

// With render.exr off, no EXR of an earlier run may sit beside the PNGs as if it were current.
int remove_exr_frames(const std::string& exr_pattern) {
  int removed = 0;
  if (!std::filesystem::is_directory(std::filesystem::path(exr_pattern).parent_path())) return 0;
  for (int f : find_pattern_frames(exr_pattern)) {
    std::error_code ec;
    if (std::filesystem::remove(expand_frame_pattern(exr_pattern, f), ec)) ++removed;
    if (ec) fail(expand_frame_pattern(exr_pattern, f), ": cannot remove this EXR frame of an earlier run: ", ec.message());
  }
  return removed;
}

}  // namespace

PreparedRender prepare_render(RenderScene& scene, RenderSettings settings) {
  if (!(scene.up.dot(Vec3f::UnitY()) > 0.999f))
    fail(scene.name, ": /gravity: the renderer's sky and ground assume +y is up; gravity must point along -y");
  if (scene.frames.empty()) fail(scene.name, ": no frames to render");
  PreparedRender p;
  p.scene = &scene;
  if (settings.camera.empty())
    settings.camera.push_back(
        auto_camera(scene_bounds(scene), scene.up, 40.0f, float(settings.width) / float(settings.height)));
  settings.camera_up = scene.up;
  settings.volume.frame_seconds = 1.0 / scene.fps;  // the shutter's unit
  settings.volume.gravity = scene.gravity;
  settings.environment.ground_height = settings.ground_height.value_or(lowest_point(scene, 1));
  p.settings = std::move(settings);
  p.diffuse_room = std::make_shared<MemoryRoom>(
      "the render", "diffuse particles", kRenderBytesPerDiffuseParticle,
      "simulate fewer (diffuse.k_ta, diffuse.k_wc, diffuse.max_particles) or render on a machine with more memory");
  return p;
}

std::vector<int> frames_to_render(const RenderScene& scene, const std::optional<std::string>& spec) {
  const std::vector<int>& available = scene.frames;
  if (!spec || available.empty()) return available;
  std::vector<int> frames;
  for (int f : parse_frame_spec(*spec, available.front(), available.back(), "--frames"))
    if (std::binary_search(available.begin(), available.end(), f)) frames.push_back(f);
  return frames;
}

std::string frame_record(const PreparedRender& p, const nlohmann::json& render_keys, int frame) {
  auto identity = [](const std::filesystem::path& path) {
    const FileIdentity id = file_identity(path);
    return nlohmann::json::array({id.size, id.mtime_ns, id.crc});
  };
  // What the keys resolved to (a camera framed from the sequence, the ground's height), and the
  // renderer's generation: a spume whose pictures differ for the same keys draws them again.
  nlohmann::json cameras = nlohmann::json::array();
  for (const CameraKey& k : p.settings.camera)
    cameras.push_back({k.time, k.position.x(), k.position.y(), k.position.z(), k.target.x(), k.target.y(),
                       k.target.z(), k.fov_y_degrees});
  // Whether EXRs are written beside the PNGs changes neither picture.
  nlohmann::json keys = render_keys;
  if (keys.is_object()) keys.erase("exr");
  nlohmann::json record = {{"render", keys},
                           {"sequence", p.scene->sequence_digest},
                           {"camera", cameras},
                           {"ground_height", p.settings.environment.ground_height},
                           {"renderer", kRenderGeneration}};
  if (p.settings.draws_diffuse()) record["diffuse"] = identity(diffuse_cache_path(p.scene->scene_out, frame));
  if (p.settings.draw_surface) {
    const std::filesystem::path fluid = expand_frame_pattern(p.scene->fluid_pattern, frame);
    // A gap filled by interpolation (fluid.allow_gaps) depends on its neighbours, which the sequence
    // digest covers.
    record["fluid"] = std::filesystem::exists(fluid) ? identity(fluid) : nlohmann::json("interpolated");
  }
  return record.dump();
}

FrameInputs LoadedFrame::inputs() const {
  FrameInputs in;
  in.index = index;
  in.time = time;
  in.fluid = fluid.positions;
  in.diffuse = has_diffuse ? &diffuse : nullptr;
  in.diffuse_velocities = diffuse_velocities;
  in.fluid_velocities = fluid.velocities;
  in.solid_set = &solid_set;
  in.solids = solids;
  return in;
}

LoadedFrame load_frame(PreparedRender& p, int f) {
  return with_context(str("frame ", f), [&] {
    return allocating("loading the frame", 0, [&] {
      LoadedFrame frame;
      frame.index = f;
      frame.time = double(f) / p.scene->fps;
      if (p.settings.draw_surface) frame.fluid = p.scene->fluid->load(f);
      if (p.settings.draws_diffuse()) {
        const auto cache = diffuse_cache_path(p.scene->scene_out, f);
        if (!std::filesystem::is_regular_file(cache))
          fail(cache.string(), ": no diffuse cache for this frame; run `spume simulate` (or `spume run`) first");
        if (p.diffuse_room) p.diffuse_room->check(peek_diffuse_cache(cache).count, cache.string());
        if (p.settings.volume.blurs() || p.settings.exr) {  // the velocities too (blur, motion vectors)
          DiffuseFrame full = read_diffuse_cache(cache);
          frame.diffuse.index = full.index, frame.diffuse.time = full.time;
          frame.diffuse.positions = std::move(full.positions), frame.diffuse.types = std::move(full.types);
          frame.diffuse_velocities = std::move(full.velocities);
        } else {
          frame.diffuse = read_diffuse_points(cache);
        }
        frame.has_diffuse = true;
      }
      if (p.settings.draw_solids) {
        Camera camera = camera_at(p.settings.camera, frame.time, p.settings.width, p.settings.height);
        frame.solid_set = solids_at_time(p.scene->solids, p.scene->bodies, frame.time);
        frame.solids = solid_meshes(frame.solid_set, camera.position, p.settings.environment.sun_direction);
      }
      return frame;
    });
  });
}

RenderStageSummary run_render_stage(PreparedRender& prepared, const nlohmann::json& render_keys,
                                    const std::vector<int>& frames, const RenderStageOptions& options) {
  const Stopwatch start;
  const RenderScene& scene = *prepared.scene;
  const RenderSettings& settings = prepared.settings;
  const std::string pattern = (scene.scene_out / settings.frame_pattern).string();
  const std::string exr_pattern = (scene.scene_out / settings.exr_pattern()).string();
  RenderStageSummary summary;
  if (!settings.exr) summary.exr_removed = remove_exr_frames(exr_pattern);
  if (frames.empty()) return summary;
  const std::filesystem::path frames_dir = std::filesystem::path(expand_frame_pattern(pattern, 0)).parent_path();

  FrameRenderer renderer(settings);
  Progress progress("render " + scene.name, frames.size(), options.quiet);
  bool any_reconstructed = false, any_gl = false, any_volume = false;
  FrameReport total;  // stage seconds summed over the written frames

  // A frame on disk is kept only when it records exactly what this render would make it from. Decided
  // once a frame, ahead of the loop where needed: the next frame to draw loads while this one renders.
  std::vector<std::string> records(frames.size());
  std::vector<int8_t> draw(frames.size(), -1);  // -1 not decided yet
  auto needs_drawing = [&](size_t k) {
    if (draw[k] < 0) {
      records[k] = frame_record(prepared, render_keys, frames[k]);
      draw[k] = options.overwrite || read_png_record(expand_frame_pattern(pattern, frames[k])) != records[k] ||
                (settings.exr && read_frame_exr_record(expand_frame_pattern(exr_pattern, frames[k])) != records[k]);
    }
    return draw[k] == 1;
  };
  // With one thread, nothing runs beside the frame being drawn.
  const bool overlap = thread_count() > 1;
  FramePrefetch loads(prepared, overlap);
  PngWriterThread pngs(overlap);
  int in_flight = -1;  // the frame whose PNG pngs is writing
  auto finish_png = [&] {
    if (in_flight >= 0) with_context(str("frame ", in_flight), [&] { pngs.finish(); });
    in_flight = -1;
  };
  // A frame that fails stops the render; the one before it is finished first (on disk, with its row).
  try {
    for (size_t k = 0; k < frames.size(); ++k) {
      const int f = frames[k];
      const std::filesystem::path path = expand_frame_pattern(pattern, f);
      if (summary.first_frame.empty()) summary.first_frame = path, summary.first_frame_number = f;
      if (!needs_drawing(k)) {
        finish_png();  // progress in frame order
        ++summary.skipped;
        progress.update(k + 1, "current, skipped");
        continue;
      }
      const Stopwatch frame_start;
      TakenFrame taken = loads.take(f);  // its errors name the frame
      if (settings.exr && taken.frame.fluid.size() > 0 && !taken.frame.fluid.has_velocities())
        messages::warning(str(scene.fluid_pattern, ": the fluid files hold no velocities, so the EXR frames' "
                              "motion vectors show the water still"));
      size_t next = k + 1;
      while (next < frames.size() && !needs_drawing(next)) ++next;
      if (next < frames.size()) loads.start(frames[next]);
      FrameReport report;
      RenderedFrame image = with_context(str("frame ", f), [&] {
        return allocating("rendering", 0, [&] { return renderer.render_frame(taken.frame.inputs(), &report); });
      });
      // The EXR goes first, so a frame whose PNG is on disk has both.
      std::function<void()> exr;
      if (image.layers)
        exr = [path = expand_frame_pattern(exr_pattern, f), layers = std::move(*image.layers),
               provenance = FrameProvenance{scene.name, records[k]}] { write_frame_exr(path, layers, provenance); };
      finish_png();
      // The frame's time on this thread: waiting for its load, then drawing it.
      const double frame_seconds = frame_start.seconds();
      pngs.write(path, std::move(image.image), records[k], std::move(exr), [&, f, k, path, report, frame_seconds, load = taken.load_seconds](double write) {
        // Every frame once it is on disk, so a run stopped midway keeps the times of what it drew.
        merge_render_stats(scene.scene_out, {{.frame = f,
                                              .triangles = report.triangles,
                                              .spheres = report.spheres,
                                              .load = load,
                                              .reconstruct = report.reconstruct_seconds,
                                              .surface = report.surface_seconds,
                                              .volume = report.volume_seconds,
                                              .composite = report.composite_seconds,
                                              .write = write,
                                              .total = frame_seconds}});
        any_reconstructed |= report.reconstructed;
        any_gl |= report.used_gl;
        any_volume |= report.volume;
        total.reconstruct_seconds += report.reconstruct_seconds;
        total.surface_seconds += report.surface_seconds;
        add_surface_stages(total.surface, report.surface);
        total.volume_seconds += report.volume_seconds;
        ++summary.written;
        if (!options.quiet) std::printf("Saved: %s\n", path.string().c_str()), std::fflush(stdout);
        progress.update(k + 1, str(report.triangles, " triangles, ", report.spheres, " diffuse spheres"));
      });
      in_flight = f;
    }
    finish_png();
  } catch (...) {
    try {
      finish_png();
    } catch (...) {  // the first error is the one to report
    }
    throw;
  }
  // Frames of the sequence left out of this render that no longer match the scene.
  for (int f : scene.frames) {
    if (std::binary_search(frames.begin(), frames.end(), f)) continue;
    const std::filesystem::path path = expand_frame_pattern(pattern, f);
    if (!std::filesystem::exists(path)) continue;
    // A frame whose cache was removed (for disk room) cannot be checked: it counts as not current.
    if (settings.draws_diffuse() && !std::filesystem::exists(diffuse_cache_path(scene.scene_out, f))) {
      ++summary.stale_elsewhere;
      continue;
    }
    const std::string record = frame_record(prepared, render_keys, f);
    const std::filesystem::path exr = expand_frame_pattern(exr_pattern, f);
    const bool current = read_png_record(path) == record &&
                         (!settings.exr || !std::filesystem::exists(exr) || read_frame_exr_record(exr) == record);
    summary.stale_elsewhere += !current;
  }
  const auto per_frame = [&](double seconds) {
    return str(" (", int(std::lround(1e3 * seconds / std::max(summary.written, 1))), " ms per frame)");
  };
  if (any_reconstructed) summary.stages.push_back("surface reconstruction" + per_frame(total.reconstruct_seconds));
  if (any_gl) {
    const SurfacePassStats& t = total.surface;
    const auto ms = [&](double seconds) { return int(std::lround(1e3 * seconds / std::max(summary.written, 1))); };
    summary.stages.push_back(
        "OSMesa surface pass" + per_frame(total.surface_seconds) +
        str(": context ", ms(t.seconds_context), ", upload ", ms(t.seconds_upload), ", shadow ", ms(t.seconds_shadow),
            ", opaque ", ms(t.seconds_opaque), ", water back ", ms(t.seconds_water_back), ", water front ",
            ms(t.seconds_water_front), ", resolve ", ms(t.seconds_resolve), ", read-back ", ms(t.seconds_readback)));
  }
  if (!any_gl && summary.written > 0) summary.stages.push_back("CPU sky and ground (nothing showed a surface)");
  if (any_volume)
    summary.stages.push_back((settings.volume.blurs() ? "volume pass (exact, motion blur)"
                              : settings.volume.integrator == VolumeIntegrator::Exact ? "volume pass (exact)"
                                                                                      : "volume pass (march)") +
                             per_frame(total.volume_seconds));
  summary.seconds = start.seconds();
  progress.finish(str(summary.written, " written, ", summary.skipped, " skipped -> ", frames_dir.string()));
  return summary;
}

}  // namespace spume
