#pragma once
// OpenVDB is loaded only by the runs that read or write .vdb files. Mapping libopenvdb costs every
// process about 26 MiB of resident pages (its 25 MiB of symbols and relocations are read in full at
// load), a sixth of a small simulate; so the code that includes OpenVDB (sim/io/vdb/) is built as a
// module, libspume_vdb.so beside the spume executable, opened at the first .vdb read or written.
// Programs that link that code in (the tests, the fuzzers, the benchmarks) use it directly.
//
// The module calls back into the program for spume's own functions (errors, atomic files, contained
// reads), so a program that opens it exports its symbols (CMake ENABLE_EXPORTS): one copy of every
// function and of the state behind it.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "sim/core/frames.h"
#include "sim/io/fog_volumes.h"
#include "sim/io/vdb_points.h"

namespace spume {

// What the module offers: the functions of vdb_points.h, vdb_points_writer.h and fog_volumes.h that
// need OpenVDB. Errors are thrown as spume::Error, as by the functions they stand behind.
struct VdbModuleApi {
  uint64_t layout;  // vdb_module_layout() of the module's build: the types below must agree
  VdbContents (*read_contents)(const std::filesystem::path& path, const std::string& grid, VdbPointsInfo* info);
  FluidFrame (*read_points)(const std::filesystem::path& path, const std::string& grid, VdbPointsInfo* info);
  std::string (*points_bytes)(const DiffuseFrame& frame, float voxel_size, std::span<const float> ages);
  std::string (*fog_bytes)(const DiffuseFrame& frame, const FogLook& look);
};

// A fingerprint of the table and of the types it passes: a module from another build of spume whose
// types differ is refused instead of misread.
constexpr uint64_t vdb_module_layout() {
  constexpr uint64_t kTableVersion = 1;  // bump when a function is added or changes its arguments
  return kTableVersion << 48 ^ uint64_t(sizeof(FluidFrame)) << 36 ^ uint64_t(sizeof(DiffuseFrame)) << 24 ^
         uint64_t(sizeof(VdbContents)) << 12 ^ uint64_t(sizeof(VdbPointsInfo)) ^ uint64_t(sizeof(FogLook)) << 6;
}

// The module's one exported symbol.
inline constexpr const char* kVdbModuleEntry = "spume_vdb_module_api";
inline constexpr const char* kVdbModuleFile = "libspume_vdb.so";

// The table: the linked-in code when the program has it, else the module beside the executable,
// opened once. Throws Error naming the module's path and what went wrong when it cannot be opened.
const VdbModuleApi& vdb_module();

}  // namespace spume

extern "C" const spume::VdbModuleApi* spume_vdb_module_api();
