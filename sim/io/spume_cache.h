#pragma once
// spume's own binary frame caches. Little-endian, no padding, arrays stored whole (one write each).
//
// Fluid cache (.spf), header 40 bytes:
//   offset  0  char[8]  magic "SPUMEFL1"
//   offset  8  u32      version (1)
//   offset 12  i32      frame index
//   offset 16  f64      time (s)
//   offset 24  f32      particle radius (m)
//   offset 28  u64      particle count n
//   offset 36  u32      flags: bit 0 velocities, bit 1 ids, bit 2 masses (other bits must be 0)
//   then, for present arrays only, in this order:
//     ids u32[n] (if bit 1), positions f32[3n], velocities f32[3n] (if bit 0), masses f32[n] (if bit 2)
//   then u32 CRC-32 (zlib crc32) of every byte before it.
//
// Diffuse cache (.spd), version 2 (compact), header 136 bytes:
//   offset  0  char[8]  magic "SPUMEDF1"
//   offset  8  u32      version (2)
//   offset 12  i32      frame index
//   offset 16  f64      time (s)
//   offset 24  u64      particle count n
//   offset 32  u64[3]   count per type (spray, foam, bubble); they sum to n
//   offset 56  u32      encoding: 0 exact, 1 quantized (io/diffuse_quantized.h states the errors)
//   offset 60  f64[3]   position origin (m), then f64 position step (m), f64 velocity step (m/s),
//                       f64 life origin (s), f64 life step (s): all 0 when exact
//   offset 108 u32[3]   cells per axis, then offset 120 u64 occupied cells (0 when exact)
//   then columns (io/column_codec.h: shuffled, zstd-compressed Blosc chunks), in this order:
//     exact:     ids u64[n], positions f32[3n], velocities f32[3n], lifetimes f32[n], types u8[n]
//     quantized: cell key steps u64[cells], cell counts u32[cells], position offsets u8[3n] (x, y, z
//                planes), velocities i16[3n] (planes), lifetimes u16[n], types (2 bits) u8[ceil(n/4)], ids u64[n]
//   then u32 CRC-32 of every byte before it.
// Quantized caches store particles sorted by cell; exact ones in the frame's order.
//
// Version 1 (raw, 37 bytes a particle; still read, no longer written), header 56 bytes: the first 56
// bytes as above, then ids u64[n], positions f32[3n], velocities f32[3n], lifetimes f32[n], types u8[n]
// (0..2), then the CRC-32.
//
// A fluid cache's (and a version 1 diffuse cache's) size is fully determined by the header, so readers
// check it before allocating anything; a version 2 diffuse cache is checked against its CRC first.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include "sim/core/frames.h"
#include "sim/io/column_codec.h"
#include "sim/io/diffuse_quantized.h"

namespace spume {

constexpr uint32_t kFluidCacheVersion = 1;
constexpr uint32_t kDiffuseCacheVersion = 2;     // written
constexpr uint32_t kRawDiffuseCacheVersion = 1;  // still read
enum FluidCacheFlags : uint32_t { kCacheHasVelocities = 1u, kCacheHasIds = 2u, kCacheHasMasses = 4u };

struct FluidCacheHeader {
  uint32_t version = kFluidCacheVersion;
  int32_t frame_index = 0;
  double time = 0.0;
  float particle_radius = 0.0f;
  uint64_t count = 0;
  uint32_t flags = 0;
};

struct DiffuseCacheHeader {
  uint32_t version = kDiffuseCacheVersion;
  int32_t frame_index = 0;
  double time = 0.0;
  uint64_t count = 0;
  std::array<uint64_t, kDiffuseTypeCount> count_by_type{};
  bool quantized = false;            // version 2: positions, velocities and lifetimes quantized
  DiffuseQuantization quantization;  // version 2 quantized only
  uint64_t occupied_cells = 0;
};

// Writes frame (its index and time go into the header) with the given particle radius.
void write_fluid_cache(const std::filesystem::path& path, const FluidFrame& frame, float particle_radius);
// Reads and verifies (magic, version, size, CRC, finite values, unique ids); *header receives the header.
FluidFrame read_fluid_cache(const std::filesystem::path& path, FluidCacheHeader* header = nullptr);
// Header only, checked against the file size (for `spume info`).
FluidCacheHeader peek_fluid_cache(const std::filesystem::path& path);

// position_step 0 writes the frame exactly (compressed, in its order); > 0 quantizes it with that step
// (the pipeline uses the fluid particle radius / kPositionStepsPerRadius), sorted by cell. A frame too
// large for the quantization grid (diffuse_quantized.h) is written exactly.
void write_diffuse_cache(const std::filesystem::path& path, const DiffuseFrame& frame, double position_step = 0.0);
// The bytes write_diffuse_cache writes (CRC included), so that a caller can encode the frame while it
// holds it and hand the writing to another thread; `where` names the file in errors.
CacheBytes encode_diffuse_cache(const DiffuseFrame& frame, double position_step, const std::string& where);
// Reads versions 1 and 2; any other version is refused naming the file and what to do.
DiffuseFrame read_diffuse_cache(const std::filesystem::path& path, DiffuseCacheHeader* header = nullptr);
// Positions and types only (what a renderer draws), checked as read_diffuse_cache checks them: of a
// quantized cache the other columns are not decoded. Same particles, in the same order, as
// read_diffuse_cache.
DiffusePoints read_diffuse_points(const std::filesystem::path& path, DiffuseCacheHeader* header = nullptr);
DiffuseCacheHeader peek_diffuse_cache(const std::filesystem::path& path);

}  // namespace spume
