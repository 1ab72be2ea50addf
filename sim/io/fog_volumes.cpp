#include "sim/io/fog_volumes.h"

#include <algorithm>
#include <cmath>

#include <openvdb/version.h>  // the version macros only: OpenVDB itself is in the module (vdb_module.h)

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/io/vdb_module.h"

namespace spume {
namespace {

// Bump when the grids, their names or the splat (io/vdb/fog_encoder.cpp) change.
constexpr int kFogLayout = 1;

}  // namespace

void sphere_voxel_weights(const Vec3f& centre, float radius, float voxel, std::vector<VoxelWeight>& out) {
  out.clear();
  const double c[3] = {double(centre.x()) / voxel, double(centre.y()) / voxel, double(centre.z()) / voxel};
  const double r = double(radius) / voxel;  // in voxels
  if (r <= 1.0) {
    // Trilinear: the 8 voxel centres around the sphere's, weights summing to one, centroid kept.
    int base[3];
    double f[3];
    for (int a = 0; a < 3; ++a) base[a] = int(std::floor(c[a])), f[a] = c[a] - base[a];
    for (int corner = 0; corner < 8; ++corner) {
      double w = 1.0;
      std::array<int, 3> ijk;
      for (int a = 0; a < 3; ++a) {
        const int up = (corner >> a) & 1;
        ijk[size_t(a)] = base[a] + up;
        w *= up ? f[a] : 1.0 - f[a];
      }
      if (w > 0.0) out.push_back({ijk, w});
    }
  } else {
    // Every voxel whose centre lies within r + 1/2: weight ramps from 1 (centre half a voxel inside
    // the rim) to 0 (half a voxel outside), then normalised.
    double sum = 0.0;
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) lo[a] = int(std::floor(c[a] - r - 0.5)), hi[a] = int(std::ceil(c[a] + r + 0.5));
    for (int i = lo[0]; i <= hi[0]; ++i)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int k = lo[2]; k <= hi[2]; ++k) {
          const double d = std::sqrt((i - c[0]) * (i - c[0]) + (j - c[1]) * (j - c[1]) + (k - c[2]) * (k - c[2]));
          const double w = std::clamp(r - d + 0.5, 0.0, 1.0);
          if (w > 0.0) out.push_back({{i, j, k}, w}), sum += w;
        }
    for (VoxelWeight& v : out) v.weight /= sum;  // sum > 0: the nearest centre is within sqrt(3)/2 < r
  }
}

std::vector<VoxelWeight> sphere_voxel_weights(const Vec3f& centre, float radius, float voxel) {
  std::vector<VoxelWeight> out;
  sphere_voxel_weights(centre, radius, voxel, out);
  return out;
}

std::string fog_volumes_format(const FogLook& look) {
  return str("spume-fog ", kFogLayout, ", OpenVDB ", OPENVDB_LIBRARY_VERSION_STRING, ", voxel ", look.voxel,
             ", radii ", look.radius[0], " ", look.radius[1], " ", look.radius[2], ", alpha ", look.alpha);
}

std::string fog_volume_bytes(const DiffuseFrame& frame, const FogLook& look) { return vdb_module().fog_bytes(frame, look); }

void write_fog_volumes(const std::filesystem::path& path, const DiffuseFrame& frame, const FogLook& look) {
  const std::string bytes = with_context(path.string(), [&] { return fog_volume_bytes(frame, look); });
  write_file_atomically(path, [&](std::ostream& out) { out.write(bytes.data(), std::streamsize(bytes.size())); });
}

}  // namespace spume
