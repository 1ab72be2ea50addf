// libFuzzer target: spume's caches (.spf fluid, .spd diffuse; io/spume_cache.h). A random input
// almost never carries a valid CRC-32 trailer, which would stop every read at the checksum; so each
// input is also read with its last four bytes replaced by the CRC of the rest, reaching the parsing
// behind the check.
#include <zlib.h>

#include <cstring>
#include <vector>

#include "tests/fuzz/fuzz_file.h"
#include "sim/io/particle_file.h"
#include "sim/io/spume_cache.h"

namespace {

void read_all(const uint8_t* data, size_t size) {
  using namespace spume;
  fuzz::read_as_file(data, size, ".spf", [](const std::filesystem::path& p) {
    fuzz::expect_clean([&] { read_fluid_file(p); });
    fuzz::expect_clean([&] { peek_fluid_cache(p); });
    fuzz::expect_clean([&] { describe_particle_file(p); });
  });
  fuzz::read_as_file(data, size, ".spd", [](const std::filesystem::path& p) {
    fuzz::expect_clean([&] { read_diffuse_cache(p); });
    fuzz::expect_clean([&] { peek_diffuse_cache(p); });
    fuzz::expect_clean([&] { describe_particle_file(p); });
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  read_all(data, size);
  if (size >= 4) {
    std::vector<uint8_t> fixed(data, data + size);
    const uint32_t crc = uint32_t(crc32(0L, fixed.data(), uInt(size - 4)));
    std::memcpy(fixed.data() + size - 4, &crc, 4);  // little-endian machine, little-endian format
    read_all(fixed.data(), size);
  }
  return 0;
}
