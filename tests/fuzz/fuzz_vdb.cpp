// libFuzzer target: OpenVDB point caches (io/vdb_points.h) read directly and through the format dispatch
// of `spume info`, in-process: the child process that reads such files first in the spume command
// (sim/io/contained_read.h) is not asked for here, so an input that trips one of the assertions
// Debian's OpenVDB keeps aborts, and libFuzzer reports it. spume handles such inputs by design
// (tests/e2e/mantaflow_cache_test.cpp keeps two and 48 random ones), so they are not kept in regressions/.
#include "tests/fuzz/fuzz_file.h"
#include "sim/io/particle_file.h"
#include "sim/io/vdb_points.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace spume;
  return fuzz::read_as_file(data, size, ".vdb", [](const std::filesystem::path& p) {
    fuzz::expect_clean([&] { read_vdb_points(p, ""); });
    fuzz::expect_clean([&] { read_fluid_file(p); });
    fuzz::expect_clean([&] { describe_particle_file(p); });
  });
}
