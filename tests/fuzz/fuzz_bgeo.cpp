// libFuzzer target: classic BGEO (io/bgeo.h) as a fluid frame, as a diffuse frame, its header alone,
// and through the format dispatch of `spume info`.
#include "tests/fuzz/fuzz_file.h"
#include "sim/io/bgeo.h"
#include "sim/io/particle_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace spume;
  return fuzz::read_as_file(data, size, ".bgeo", [](const std::filesystem::path& p) {
    fuzz::expect_clean([&] { read_fluid_file(p); });
    fuzz::expect_clean([&] { read_bgeo_info(p); });
    fuzz::expect_clean([&] { read_bgeo_diffuse(p); });
    fuzz::expect_clean([&] { describe_particle_file(p); });
  });
}
