// libFuzzer target: Houdini 12+ geometry (io/houdini_geometry.h: binary JSON, plain, gzipped or in a
// .bgeo.sc Blosc container) read directly and through the format dispatch of `spume info`.
#include "tests/fuzz/fuzz_file.h"
#include "sim/io/houdini_geometry.h"
#include "sim/io/particle_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace spume;
  return fuzz::read_as_file(data, size, ".bgeo", [](const std::filesystem::path& p) {
    fuzz::expect_clean([&] { read_houdini_geometry(p); });
    fuzz::expect_clean([&] { read_fluid_file(p); });
    fuzz::expect_clean([&] { describe_particle_file(p); });
  });
}
