#include "render/stage/render_stats.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <map>
#include <string>

#include "sim/core/atomic_file.h"
#include "sim/core/output_lock.h"
#include "sim/core/error.h"
#include "sim/io/cache_layout.h"

namespace spume {
namespace {

constexpr const char* kHeader =
    "frame,triangles,diffuse_spheres,load_ms,reconstruct_ms,surface_ms,volume_ms,composite_ms,write_ms,total_ms";

std::string row_text(const RenderStatsRow& r) {
  const auto ms = [](double seconds) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f", 1e3 * seconds);
    return std::string(text);
  };
  return str(r.frame, ",", r.triangles, ",", r.spheres, ",", ms(r.load), ",", ms(r.reconstruct), ",", ms(r.surface),
             ",", ms(r.volume), ",", ms(r.composite), ",", ms(r.write), ",", ms(r.total));
}

// The rows of an earlier file with this header, by frame (none when it is missing or another format).
std::map<int, std::string> earlier_rows(const std::filesystem::path& path) {
  std::map<int, std::string> rows;
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line != kHeader) return rows;
  while (std::getline(in, line)) {
    int frame = 0;
    const auto [end, error] = std::from_chars(line.data(), line.data() + line.size(), frame);
    if (error == std::errc() && end != line.data() + line.size() && *end == ',') rows[frame] = line;
  }
  return rows;
}

}  // namespace

void merge_render_stats(const std::filesystem::path& scene_out, std::vector<RenderStatsRow> rows) {
  if (rows.empty()) return;
  update_under_gate(scene_out, [&] {
    const std::filesystem::path path = render_stats_path(scene_out);
    std::map<int, std::string> merged = earlier_rows(path);
    for (const RenderStatsRow& r : rows) merged[r.frame] = row_text(r);
    write_file_atomically(path, [&](std::ostream& out) {
      out << kHeader << "\n";
      for (const auto& [frame, line] : merged) out << line << "\n";
    });
  });
}

}  // namespace spume
