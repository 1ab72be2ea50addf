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
// Diffuse cache (.spd), header 56 bytes:
//   offset  0  char[8]  magic "SPUMEDF1"
//   offset  8  u32      version (1)
//   offset 12  i32      frame index
//   offset 16  f64      time (s)
//   offset 24  u64      particle count n
//   offset 32  u64[3]   count per type (spray, foam, bubble); they sum to n
//   then ids u64[n], positions f32[3n], velocities f32[3n], lifetimes f32[n], types u8[n] (0..2)
//   then u32 CRC-32 of every byte before it.
//
// The file size is fully determined by the header, so readers check it before allocating anything.
#include <array>
#include <cstdint>
#include <filesystem>

#include "sim/core/frames.h"

namespace spume {

constexpr uint32_t kFluidCacheVersion = 1;
constexpr uint32_t kDiffuseCacheVersion = 1;
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
};

// Writes frame (its index and time go into the header) with the given particle radius.
void write_fluid_cache(const std::filesystem::path& path, const FluidFrame& frame, float particle_radius);
// Reads and verifies (magic, version, size, CRC, finite values, unique ids); *header receives the header.
FluidFrame read_fluid_cache(const std::filesystem::path& path, FluidCacheHeader* header = nullptr);
// Header only, checked against the file size (for `spume info`).
FluidCacheHeader peek_fluid_cache(const std::filesystem::path& path);

void write_diffuse_cache(const std::filesystem::path& path, const DiffuseFrame& frame);
DiffuseFrame read_diffuse_cache(const std::filesystem::path& path, DiffuseCacheHeader* header = nullptr);
DiffuseCacheHeader peek_diffuse_cache(const std::filesystem::path& path);

}  // namespace spume
