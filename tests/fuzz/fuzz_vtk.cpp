// libFuzzer target: legacy VTK (io/vtk.h), ASCII and binary, through read_fluid_file and `spume info`.
#include "tests/fuzz/fuzz_file.h"
#include "sim/io/particle_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace spume;
  return fuzz::read_as_file(data, size, ".vtk", [](const std::filesystem::path& p) {
    fuzz::expect_clean([&] { read_fluid_file(p); });
    fuzz::expect_clean([&] { describe_particle_file(p); });
  });
}
