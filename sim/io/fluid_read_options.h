#pragma once
// How fluid files are read beyond their format: which axis the cache calls up (spume's world is
// Y-up: gravity, tanks, the renderer's sky and ground), for OpenVDB, which point grid to read, and
// whether stored masses are kept.
#include <string>

#include "sim/core/frames.h"

namespace spume {

enum class UpAxis { Y, Z };

struct FluidReadOptions {
  UpAxis up = UpAxis::Y;  // Z: the cache is Z-up (Blender) and is turned to Y-up as it is read
  std::string vdb_grid;   // "": every point data grid of a .vdb; else the one of this name
  bool stored_masses = true;  // false: masses are dropped as read (far from rho0 (2r)^3: io/stored_mass_check.h)
  bool operator==(const FluidReadOptions&) const = default;
};

inline const char* up_axis_name(UpAxis up) { return up == UpAxis::Z ? "z" : "y"; }

// Z-up to Y-up, a rotation by -90 degrees about x: (x, y, z) -> (x, z, -y), positions and velocities.
inline Vec3f z_up_to_y_up(const Vec3f& p) { return Vec3f(p.x(), p.z(), -p.y()); }

inline void to_y_up(FluidFrame& frame, UpAxis up) {
  if (up == UpAxis::Y) return;
  for (Vec3f& p : frame.positions) p = z_up_to_y_up(p);
  for (Vec3f& v : frame.velocities) v = z_up_to_y_up(v);
}

}  // namespace spume
