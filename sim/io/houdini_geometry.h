#pragma once
// Houdini's geometry of Houdini 12 and later: binary JSON (io/houdini_json.h) as a plain .bgeo, gzipped
// (.bgeo.gz) or Blosc-compressed (.bgeo.sc, io/houdini_scf.h). Points are read; primitives (meshes,
// packed objects) are counted and left out.
//
// The geometry is a key/value array: "pointcount", an "info" map Houdini writes for itself ("bounds" of
// the whole geometry as xmin xmax ymin ymax zmin zmax, "attribute_ranges" as text, "primcount_summary"),
// "topology", and "attributes" whose "pointattributes" list each attribute as [definition (scope, type,
// name, options), body ("size", "storage", "defaults", "values": io/houdini_values.h)].
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sim/core/frames.h"
#include "sim/core/vec.h"
#include "sim/io/point_attribute.h"

namespace spume {

struct HoudiniGeometryInfo {
  std::string container;       // "Blosc (.bgeo.sc)", "gzip" or "none"
  size_t chunks = 0;           // Blosc chunks
  size_t json_bytes = 0;       // the binary JSON, decompressed
  std::string file_version;    // Houdini's version that wrote it
  size_t point_count = 0;      // points in the file
  size_t primitive_count = 0;
  std::string primitive_summary;                  // Houdini's, e.g. "12,854 Polygons"
  std::vector<PointAttribute> point_attributes;   // type: the storage ("fpreal32", "int32") or kind ("string")
  std::string velocity_attribute;                 // the velocity name read (io/attribute_names.h); empty when none
  size_t points_without_id = 0;  // points with a negative id (Houdini's -1: no id), left out of the frame
  Aabb point_bounds;             // of every point in the file
  Aabb velocity_range;           // per component, over every point in the file (empty without velocity)
  std::optional<Aabb> info_bounds;      // the info block's bounds, when given
  std::string info_attribute_ranges;    // the info block's attribute_ranges text, when given
};

// True when the file's bytes (after gzip, or a .bgeo.sc container) are Houdini binary JSON.
bool is_houdini_geometry(const std::filesystem::path& path);

// The particles: positions from P; velocities from `v`, `vel` or `velocity` (3 numbers); ids from
// `id` (an integer attribute; points with a negative id are not particles: left out, and counted in
// *info); masses from `mass`. Any storage Houdini writes is converted. The frame is validated.
FluidFrame read_houdini_geometry(const std::filesystem::path& path, HoudiniGeometryInfo* info = nullptr);

}  // namespace spume
