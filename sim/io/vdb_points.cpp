#include "sim/io/vdb_points.h"

#include <array>
#include <fstream>

#include "sim/io/vdb_module.h"

namespace spume {

bool has_vdb_magic(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 8> magic{};
  if (!in.read(reinterpret_cast<char*>(magic.data()), magic.size())) return false;
  // OPENVDB_MAGIC (0x56444220) as a little-endian int64: " BDV" and four zero bytes.
  constexpr std::array<unsigned char, 8> kMagic = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};
  return magic == kMagic;
}

VdbContents read_vdb_contents(const std::filesystem::path& path, const std::string& grid, VdbPointsInfo* info) {
  return vdb_module().read_contents(path, grid, info);
}

FluidFrame read_vdb_points(const std::filesystem::path& path, const std::string& grid, VdbPointsInfo* info) {
  return vdb_module().read_points(path, grid, info);
}

}  // namespace spume
