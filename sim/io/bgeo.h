#pragma once
// Classic Houdini/partio BGEO (version 5), as SPlisHSPlasH and Houdini's .bhclassic export write it.
//
// Layout (all values big-endian; the whole file may be gzip-compressed, detected by 1f 8b):
//   "Bgeo" 'V', int32 version (5), then int32 counts: points, primitives, point groups, primitive
//   groups, point attributes, vertex attributes, primitive attributes, detail attributes.
//   Per point attribute: int16 name length, name, uint16 size (words per point), int32 type
//   (0 float, 1 int, 5 vector; 4 indexed string: int32 string count and int16-length strings instead of
//   defaults), then `size` int32 default words for types 0/1/5.
//   Points: x y z w as float32, then each attribute's words in declaration order.
//   Without primitives: the detail attribute definitions (same form), one record of their words, the
//   point groups, the primitive groups and the end marker 00 FF. A group (SideFX's GPD library for
//   V5): a byte 01 only when it is ordered, uint16 name length, name, int32 bit count, then a bit mask
//   of ceil(bits / 32) uint32 words, element i at bit i & 31 of word i >> 5; an ordered group then has
//   int32 count and int32 indices (a negative one followed by an int32 profile).
// Houdini's JSON geometry (binary 7F 'N' 'S' 'J', or ASCII '{'/'[') is detected and refused here: the binary
// form is io/houdini_geometry.h's, which io/particle_file.h picks by the first bytes.
#include <filesystem>
#include <span>
#include <vector>

#include "sim/core/frames.h"
#include "sim/core/vec.h"
#include "sim/io/point_attribute.h"

namespace spume {

struct BgeoInfo {
  bool gzipped = false;
  int version = 0;
  size_t point_count = 0;
  int primitive_count = 0;
  int point_group_count = 0;
  int primitive_group_count = 0;
  std::vector<PointAttribute> point_attributes;   // type "float", "int", "vector" or "index"
  std::vector<PointAttribute> detail_attributes;  // empty when trailing data was skipped
  std::vector<std::pair<std::string, size_t>> point_groups;  // name, member count
  bool trailing_data_skipped = false;             // primitives present: only points were parsed
  Aabb bounds;                                    // of the point positions
};

// Positions; velocities from `v` (preferred) or `velocity` (3 float/vector words); ids from the int
// attribute `id` (negative ids are rejected); masses from float `mass`. Other attributes are ignored
// (listed in *info). The frame's index and time are 0: BGEO carries neither.
FluidFrame read_bgeo(const std::filesystem::path& path, BgeoInfo* info = nullptr);

// Header, attribute list and bounds without building a frame (works for fluid and diffuse files).
BgeoInfo read_bgeo_info(const std::filesystem::path& path);

// Reads a file written by write_bgeo(path, DiffuseFrame): needs `v`, `type` and `lifetime`; the id is
// rebuilt from `id` (parent), `birth` and `sample` (missing ones count as 0).
DiffuseFrame read_bgeo_diffuse(const std::filesystem::path& path);

// Gzip-compressed BGEO with point attributes `id` (int, when the frame has ids), `v` (vector, when it
// has velocities) and `mass` (float, when it has masses).
void write_bgeo(const std::filesystem::path& path, const FluidFrame& frame);

// Gzip-compressed BGEO with point attributes `v` (vector), `type` (int: 0 spray, 1 foam, 2 bubble),
// `lifetime` (float, s remaining), `id` (int, parent fluid id), `birth` (int, birth step), `sample`
// (int); with `ages` (s, one per particle: io/diffuse_age.h) also Houdini's `age` and `life` (float, s:
// age + lifetime, so age / life runs from 0 towards 1); and the point groups `spray`, `foam`, `bubble`.
void write_bgeo(const std::filesystem::path& path, const DiffuseFrame& frame, std::span<const float> ages = {});

}  // namespace spume
