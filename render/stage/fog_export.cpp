#include "render/stage/fog_export.h"

#include "sim/io/cache_layout.h"
#include "sim/io/fog_volumes.h"
#include "sim/io/spume_cache.h"

namespace spume {

namespace fs = std::filesystem;

FrameExport fog_export(const RenderSettings& settings, float voxel, const fs::path& scene_out) {
  FogLook look;
  look.voxel = voxel;
  look.alpha = settings.volume.alpha;
  for (int t = 0; t < kDiffuseTypeCount; ++t) look.radius[size_t(t)] = settings.volume.look[size_t(t)].radius;
  auto cache_of = [scene_out](int f) { return diffuse_cache_path(scene_out, f); };
  return FrameExport{.folder = "diffuse_fog", .key = "output.fog", .prefix = "fog", .extension = ".vdb",
                     .on = voxel > 0.0f, .format = {{"format", fog_volumes_format(look)}},
                     .cache_of = cache_of, .write = [cache_of, look](int f, const fs::path& file) {
                       write_fog_volumes(file, read_diffuse_cache(cache_of(f)), look);
                     }};
}

}  // namespace spume
