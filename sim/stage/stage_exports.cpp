#include "sim/stage/stage_exports.h"

#include "sim/io/bgeo.h"
#include "sim/io/cache_layout.h"
#include "sim/io/diffuse_age.h"
#include "sim/io/spume_cache.h"
#include "sim/io/stage_record.h"
#include "sim/io/vdb_points_writer.h"

namespace spume {

namespace fs = std::filesystem;

std::vector<FrameExport> diffuse_exports(const SimScene& scene, const fs::path& scene_out) {
  auto cache_of = [scene_out](int f) { return diffuse_cache_path(scene_out, f); };
  const int substeps = scene.diffuse.substeps;
  const double fps = scene.fluid.fps;
  // Both carry each particle's age and life (io/diffuse_age.h), which the step length fixes.
  const nlohmann::json clock = {{"substeps", substeps}, {"fps", fps}};
  FrameExport bgeo{.folder = "diffuse_bgeo", .key = "output.bgeo", .prefix = "diffuse", .extension = ".bgeo",
                   .on = scene.write_bgeo,
                   .format = {{"format", "classic BGEO: v type lifetime id birth sample age life"}, {"clock", clock}},
                   .cache_of = cache_of, .write = [cache_of, substeps, fps](int f, const fs::path& file) {
                     const DiffuseFrame frame = read_diffuse_cache(cache_of(f));
                     write_bgeo(file, frame, diffuse_ages(frame, substeps, fps));
                   }};
  const float voxel = vdb_points_voxel_size(scene.fluid.particle_radius);
  FrameExport vdb{.folder = "diffuse_vdb", .key = "output.vdb", .prefix = "diffuse", .extension = ".vdb",
                  .on = scene.write_vdb,
                  .format = {{"format", vdb_points_format(voxel)}, {"attributes", "P v lifetime age life id type"},
                             {"clock", clock}},
                  .cache_of = cache_of, .write = [cache_of, voxel, substeps, fps](int f, const fs::path& file) {
                    const DiffuseFrame frame = read_diffuse_cache(cache_of(f));
                    write_vdb_points(file, frame, voxel, diffuse_ages(frame, substeps, fps));
                  }};
  return {bgeo, vdb};
}

std::vector<FrameExport> fluid_exports(const SimScene& scene, const fs::path& scene_out) {
  auto cache_of = [scene_out](int f) { return fluid_cache_path(scene_out, f); };
  FrameExport bgeo{.folder = "fluid_bgeo", .key = "output.fluid_bgeo", .prefix = "fluid", .extension = ".bgeo",
                   .on = scene.write_fluid_bgeo, .format = {{"format", "classic BGEO, the fluid's attributes"}},
                   .cache_of = cache_of, .write = [cache_of](int f, const fs::path& file) {
                     write_bgeo(file, read_fluid_cache(cache_of(f)));
                   }};
  return {bgeo};
}

std::vector<int> recorded_frames(const fs::path& cache_dir, const std::vector<int>& otherwise) {
  const std::optional<StageRecord> record = read_stage_record(cache_dir);
  if (!record) return otherwise;
  std::vector<int> frames;
  for (const auto& [frame, input] : record->frame_inputs) frames.push_back(frame);
  if (frames.empty())  // a stage with no input file per frame (the fluid solver) records its range
    for (int f = record->first_frame; f <= record->last_frame; ++f) frames.push_back(f);
  return frames;
}

}  // namespace spume
