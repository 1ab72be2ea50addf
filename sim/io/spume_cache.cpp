#include "sim/io/spume_cache.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <fstream>
#include <ostream>
#include <system_error>

#include "sim/io/crc_file.h"

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/io/io_bytes.h"

namespace spume {
namespace {

using io::ByteReader;
using io::Endian;

// Arrays are written straight from memory, which is only the documented layout on little-endian hosts
// with unpadded vectors.
static_assert(std::endian::native == std::endian::little, "spume caches assume a little-endian host");
static_assert(sizeof(Vec3f) == 12, "Vec3f must be three packed floats");
static_assert(sizeof(DiffuseType) == 1);

constexpr char kFluidMagic[] = "SPUMEFL1";
constexpr char kDiffuseMagic[] = "SPUMEDF1";
constexpr size_t kFluidHeaderSize = 40;
constexpr size_t kDiffuseHeaderSize = 56;
constexpr uint32_t kKnownFlags = kCacheHasVelocities | kCacheHasIds | kCacheHasMasses;


// Input with a running CRC; the header decides the exact file size before anything is allocated.
struct CrcReader {
  std::string where;
  std::ifstream in;
  uint64_t file_size = 0;
  uint32_t crc = crc32_start();

  explicit CrcReader(const std::filesystem::path& path) : where(path.string()) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(where, ": no such file");
    file_size = std::filesystem::file_size(path, ec);
    if (ec) fail(where, ": cannot determine file size: ", ec.message());
    in.open(path, std::ios::binary);
    if (!in) fail(where, ": cannot open for reading");
  }
  void read(void* dst, size_t bytes, const char* what) {
    if (bytes == 0) return;
    if (!in.read(static_cast<char*>(dst), std::streamsize(bytes)))
      fail(where, ": read failed in ", what, " (file truncated or unreadable)");
    crc = crc32_update(crc, dst, bytes);
  }
  template <typename T>
  void read_array(std::vector<T>& v, size_t n, const char* what) {
    v.resize(n);
    read(v.data(), n * sizeof(T), what);
  }
  std::string header(size_t size, const char* magic, const char* kind) {
    std::string h(size, '\0');
    const size_t got = size_t(std::min<uint64_t>(file_size, size));
    if (got > 0) read(h.data(), got, "header");
    if (h.compare(0, 8, magic) != 0) {
      std::string found = h.substr(0, std::min<size_t>(8, got));
      for (char& c : found)
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
      fail(where, ": not a spume ", kind, " cache: magic is '", found, "'; expected '", magic, "'");
    }
    if (file_size < size) fail(where, ": truncated: ", file_size, " bytes, shorter than the ", size, "-byte header");
    return h;
  }
  // Called once the header fixes the payload: count * per_particle bytes, then the CRC.
  void check_size(uint64_t header_size, uint64_t count, uint64_t per_particle) {
    const uint64_t room = file_size - header_size;  // file_size >= header_size was checked
    if (room < 4 || count > (room - 4) / per_particle)
      fail(where, ": particle count ", count, " does not fit the file size ", file_size,
           " bytes (truncated or corrupt header)");
    const uint64_t expected = header_size + count * per_particle + 4;
    if (expected != file_size)
      fail(where, ": file is ", file_size, " bytes but its header describes ", expected, " (",
           file_size - expected, " unexpected trailing bytes)");
  }
  void check_crc() {
    uint32_t stored = 0;
    const uint32_t computed = crc;
    if (!in.read(reinterpret_cast<char*>(&stored), 4)) fail(where, ": truncated before the CRC");
    if (stored != computed)
      fail(where, ": corrupt: CRC-32 mismatch (stored ", std::hex, stored, ", computed ", computed, ")");
  }
};

size_t fluid_bytes_per_particle(uint32_t flags) {
  return 12 + (flags & kCacheHasIds ? 4 : 0) + (flags & kCacheHasVelocities ? 12 : 0) + (flags & kCacheHasMasses ? 4 : 0);
}
constexpr size_t kDiffuseBytesPerParticle = 8 + 12 + 12 + 4 + 1;

FluidCacheHeader read_fluid_header(CrcReader& r) {
  const std::string bytes = r.header(kFluidHeaderSize, kFluidMagic, "fluid");
  ByteReader h(bytes, r.where);
  h.skip(8, "magic");
  FluidCacheHeader out;
  out.version = h.read<uint32_t>("version");
  if (out.version != kFluidCacheVersion)
    fail(r.where, ": fluid cache version ", out.version, "; this build reads version ", kFluidCacheVersion);
  out.frame_index = h.read<int32_t>("frame index");
  out.time = h.read<double>("time");
  out.particle_radius = h.read<float>("particle radius");
  out.count = h.read<uint64_t>("count");
  out.flags = h.read<uint32_t>("flags");
  if (out.flags & ~kKnownFlags)
    fail(r.where, ": fluid cache flags 0x", std::hex, out.flags, "; allowed bits 0x1 velocities, 0x2 ids, 0x4 masses");
  if (!std::isfinite(out.time) || !std::isfinite(out.particle_radius) || out.particle_radius < 0.0f)
    fail(r.where, ": time ", out.time, " / particle radius ", out.particle_radius, " in the header must be finite (radius >= 0)");
  r.check_size(kFluidHeaderSize, out.count, fluid_bytes_per_particle(out.flags));
  return out;
}

DiffuseCacheHeader read_diffuse_header(CrcReader& r) {
  const std::string bytes = r.header(kDiffuseHeaderSize, kDiffuseMagic, "diffuse");
  ByteReader h(bytes, r.where);
  h.skip(8, "magic");
  DiffuseCacheHeader out;
  out.version = h.read<uint32_t>("version");
  if (out.version != kDiffuseCacheVersion)
    fail(r.where, ": diffuse cache version ", out.version, "; this build reads version ", kDiffuseCacheVersion);
  out.frame_index = h.read<int32_t>("frame index");
  out.time = h.read<double>("time");
  out.count = h.read<uint64_t>("count");
  uint64_t sum = 0;
  for (uint64_t& c : out.count_by_type) {
    c = h.read<uint64_t>("count per type");
    sum += c;
    if (c > out.count || sum > out.count)
      fail(r.where, ": counts per type exceed the particle count ", out.count, " (corrupt header)");
  }
  if (sum != out.count)
    fail(r.where, ": counts per type sum to ", sum, " but the particle count is ", out.count, " (corrupt header)");
  if (!std::isfinite(out.time)) fail(r.where, ": time ", out.time, " in the header must be finite");
  r.check_size(kDiffuseHeaderSize, out.count, kDiffuseBytesPerParticle);
  return out;
}

}  // namespace

void write_fluid_cache(const std::filesystem::path& path, const FluidFrame& frame, float particle_radius) {
  frame.validate(path.string());
  if (!std::isfinite(particle_radius) || particle_radius < 0.0f)
    fail(path.string(), ": particle radius ", particle_radius, "; must be finite and >= 0");
  uint32_t flags = 0;
  if (frame.has_velocities()) flags |= kCacheHasVelocities;
  if (frame.has_ids()) flags |= kCacheHasIds;
  if (!frame.masses.empty()) flags |= kCacheHasMasses;
  std::string header(kFluidMagic, 8);
  io::store(header, kFluidCacheVersion, Endian::Little);
  io::store(header, int32_t(frame.index), Endian::Little);
  io::store(header, frame.time, Endian::Little);
  io::store(header, particle_radius, Endian::Little);
  io::store(header, uint64_t(frame.size()), Endian::Little);
  io::store(header, flags, Endian::Little);
  write_crc_file(path, header, frame.ids, frame.positions, frame.velocities, frame.masses);
}

FluidFrame read_fluid_cache(const std::filesystem::path& path, FluidCacheHeader* header) {
  CrcReader r(path);
  const FluidCacheHeader h = read_fluid_header(r);
  const size_t n = size_t(h.count);
  FluidFrame frame;
  frame.index = h.frame_index;
  frame.time = h.time;
  if (h.flags & kCacheHasIds) r.read_array(frame.ids, n, "ids");
  r.read_array(frame.positions, n, "positions");
  if (h.flags & kCacheHasVelocities) r.read_array(frame.velocities, n, "velocities");
  if (h.flags & kCacheHasMasses) r.read_array(frame.masses, n, "masses");
  r.check_crc();
  frame.validate(r.where);
  if (header) *header = h;
  return frame;
}

FluidCacheHeader peek_fluid_cache(const std::filesystem::path& path) {
  CrcReader r(path);
  return read_fluid_header(r);
}

void write_diffuse_cache(const std::filesystem::path& path, const DiffuseFrame& frame) {
  frame.validate(path.string());
  std::string header(kDiffuseMagic, 8);
  io::store(header, kDiffuseCacheVersion, Endian::Little);
  io::store(header, int32_t(frame.index), Endian::Little);
  io::store(header, frame.time, Endian::Little);
  io::store(header, uint64_t(frame.size()), Endian::Little);
  for (size_t c : frame.count_by_type()) io::store(header, uint64_t(c), Endian::Little);
  write_crc_file(path, header, frame.ids, frame.positions, frame.velocities, frame.lifetimes, frame.types);
}

DiffuseFrame read_diffuse_cache(const std::filesystem::path& path, DiffuseCacheHeader* header) {
  CrcReader r(path);
  const DiffuseCacheHeader h = read_diffuse_header(r);
  const size_t n = size_t(h.count);
  DiffuseFrame frame;
  frame.index = h.frame_index;
  frame.time = h.time;
  r.read_array(frame.ids, n, "ids");
  r.read_array(frame.positions, n, "positions");
  r.read_array(frame.velocities, n, "velocities");
  r.read_array(frame.lifetimes, n, "lifetimes");
  r.read_array(frame.types, n, "types");
  r.check_crc();
  frame.validate(r.where);  // also rejects types >= 3 before they are counted below
  const auto counts = frame.count_by_type();
  for (int t = 0; t < kDiffuseTypeCount; ++t)
    if (counts[t] != h.count_by_type[t])
      fail(r.where, ": header says ", h.count_by_type[t], " ", to_string(DiffuseType(t)), " particles but the data has ",
           counts[t], " (corrupt)");
  if (header) *header = h;
  return frame;
}

DiffuseCacheHeader peek_diffuse_cache(const std::filesystem::path& path) {
  CrcReader r(path);
  return read_diffuse_header(r);
}

}  // namespace spume
