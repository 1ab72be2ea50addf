#include "sim/io/vdb/file_bytes.h"

#include <cstdint>
#include <cstdio>
#include <mutex>
#include <sstream>

#include <openvdb/io/Stream.h>
#include <openvdb/points/AttributeArray.h>

#include "sim/core/error.h"

namespace spume::openvdb_io {
namespace {

bool is_hex(char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'); }

// FNV-1a 64 of bytes, seeded.
uint64_t fnv1a(const std::string& bytes, size_t from, uint64_t seed) {
  uint64_t h = seed;
  for (size_t i = from; i < bytes.size(); ++i) h = (h ^ uint8_t(bytes[i])) * 1099511628211ull;
  return h;
}

// OpenVDB's header: magic (8 bytes), file version, library major and minor (4 each), a has-offsets
// byte, then the UUID as 36 characters (8-4-4-4-12 hex digits).
constexpr size_t kUuidOffset = 21, kUuidLength = 36;

void replace_uuid_with_digest(std::string& bytes) {
  if (bytes.size() < kUuidOffset + kUuidLength) fail("OpenVDB wrote a header of ", bytes.size(), " bytes only");
  for (size_t i = 0; i < kUuidLength; ++i) {
    const char c = bytes[kUuidOffset + i];
    const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
    if (dash ? c != '-' : !is_hex(c))
      fail("OpenVDB's header has no UUID where spume expects it (byte ", kUuidOffset, "): an OpenVDB version "
           "spume does not know");
  }
  const size_t rest = kUuidOffset + kUuidLength;
  const uint64_t a = fnv1a(bytes, rest, 14695981039346656037ull), b = fnv1a(bytes, rest, 0x9e3779b97f4a7c15ull);
  char uuid[kUuidLength + 1];
  std::snprintf(uuid, sizeof uuid, "%08x-%04x-%04x-%04x-%012llx", unsigned(a >> 32), unsigned(a >> 16) & 0xffffu,
                unsigned(a) & 0xffffu, unsigned(b >> 48), static_cast<unsigned long long>(b & 0xffffffffffffull));
  bytes.replace(kUuidOffset, kUuidLength, uuid, kUuidLength);
}

}  // namespace

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] {
    openvdb::initialize();
    // Mantaflow stores its int32 flag `U` with the truncate codec, which OpenVDB does not register.
    using Int32Truncate = openvdb::points::TypedAttributeArray<int32_t, openvdb::points::TruncateCodec>;
    if (!Int32Truncate::isRegistered()) Int32Truncate::registerType();
  });
}

std::string vdb_file_bytes(const openvdb::GridCPtrVec& grids) {
  std::ostringstream out(std::ios::binary);
  openvdb::io::Stream stream(out);
  stream.setCompression(openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ACTIVE_MASK);
  openvdb::MetaMap file_meta;
  file_meta.insertMeta("creator", openvdb::StringMetadata("spume"));
  stream.write(grids, file_meta);
  std::string bytes = std::move(out).str();
  replace_uuid_with_digest(bytes);
  return bytes;
}

}  // namespace spume::openvdb_io
