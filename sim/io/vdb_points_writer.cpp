#include "sim/io/vdb_points_writer.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <openvdb/version.h>  // the version macros only: OpenVDB itself is in the module (vdb_module.h)

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/io/vdb_module.h"

namespace spume {

std::string vdb_points_format(float voxel_size) {
  // Bump the layout number when the attributes, codecs or metadata written here change.
  return str("spume-vdb-points 1, OpenVDB ", OPENVDB_LIBRARY_VERSION_STRING, ", voxel ", voxel_size);
}

float vdb_points_voxel_size(float particle_radius) { return 2.0f * particle_radius; }

double vdb_position_error(float voxel_size, float coordinate) {
  const double step = double(voxel_size) / kVdbPositionSteps;
  const double ulp = std::nextafter(std::fabs(coordinate), std::numeric_limits<float>::infinity()) - std::fabs(coordinate);
  // Half a step, with 4% for the codec's own float arithmetic (it scales a float offset by 65535),
  // and half an ulp for a reader that holds the world position as a float.
  return 0.52 * step + 0.5 * ulp;
}

double vdb_velocity_error(float component) {
  return std::max(std::ldexp(std::fabs(double(component)), -11), std::ldexp(1.0, -25));
}

std::string vdb_points_bytes(const DiffuseFrame& frame, float voxel_size, std::span<const float> ages) {
  return vdb_module().points_bytes(frame, voxel_size, ages);
}

void write_vdb_points(const std::filesystem::path& path, const DiffuseFrame& frame, float voxel_size,
                      std::span<const float> ages) {
  const std::string bytes = with_context(path.string(), [&] { return vdb_points_bytes(frame, voxel_size, ages); });
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

}  // namespace spume
