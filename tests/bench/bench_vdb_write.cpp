// Writing one diffuse frame as spume's .spd cache, as OpenVDB points (output.vdb) or as fog volumes
// (output.fog: the render's default radii 0.3, 0.5 and 0.4 r, voxels of 2 r), as a whole process to
// time from outside (each mode reads the same .spd first; `read` only reads, the baseline):
//   build/bench/bench_vdb_write read|spd|vdb|fog IN.spd OUT_DIR RADIUS
// prints the file's bytes and bytes per particle. Built with -DSPUME_BUILD_BENCHMARKS=ON.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "sim/core/error.h"
#include "sim/io/fog_volumes.h"
#include "sim/io/spume_cache.h"
#include "sim/io/vdb_points_writer.h"

int main(int argc, char** argv) {
  using namespace spume;
  if (argc != 5) {
    std::fprintf(stderr, "usage: bench_vdb_write read|spd|vdb|fog IN.spd OUT_DIR RADIUS\n");
    return 2;
  }
  try {
    const std::string mode = argv[1];
    const DiffuseFrame frame = read_diffuse_cache(argv[2]);
    const std::filesystem::path out_dir = argv[3];
    const float radius = std::strtof(argv[4], nullptr);
    std::filesystem::path written;
    if (mode == "spd") write_diffuse_cache(written = out_dir / "frame.spd", frame);
    else if (mode == "vdb") write_vdb_points(written = out_dir / "frame.vdb", frame, vdb_points_voxel_size(radius));
    else if (mode == "fog") {
      const FogLook look{.voxel = 2 * radius, .radius = {0.3f * radius, 0.5f * radius, 0.4f * radius}, .alpha = 50};
      write_fog_volumes(written = out_dir / "fog.vdb", frame, look);
    } else if (mode != "read") fail("mode ", mode, ": read, spd, vdb or fog");
    if (!written.empty()) {
      const auto bytes = std::filesystem::file_size(written);
      std::printf("%s: %zu particles, %ju bytes, %.2f bytes per particle\n", written.c_str(), frame.size(),
                  uintmax_t(bytes), double(bytes) / double(std::max<size_t>(frame.size(), 1)));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_vdb_write: %s\n", e.what());
    return 1;
  }
  return 0;
}
