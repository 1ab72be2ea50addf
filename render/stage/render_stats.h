#pragma once
// OUT/<scene>/render_stats.csv: what each frame's render cost, by stage, so a look-dev or farm run can
// be planned from the last one (the simulation's stats.csv and fluid/solver_stats.csv do the same for
// the diffuse and fluid stages).
#include <cstddef>
#include <filesystem>
#include <vector>

namespace spume {

struct RenderStatsRow {
  int frame = 0;
  size_t triangles = 0, spheres = 0;
  // seconds: reading the caches, surface reconstruction, OSMesa surface pass, volume pass,
  // compositing, PNG encoding and writing, and the whole frame
  double load = 0, reconstruct = 0, surface = 0, volume = 0, composite = 0, write = 0, total = 0;
};

// Rows of frames drawn now replace those frames' rows; rows of other frames stay (a farm's chunks each
// add theirs; a file with another header is replaced). Written atomically under the folder's gate.
void merge_render_stats(const std::filesystem::path& scene_out, std::vector<RenderStatsRow> rows);

}  // namespace spume
