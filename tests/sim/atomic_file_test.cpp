// Atomic writes: the temporary file is named after the host and the process (farm nodes share
// folders), and only the finished file appears under the final name.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

TEST(AtomicFile, TemporaryNameCarriesHostAndPid) {
  const testing::TempDir temp;
  const std::filesystem::path& dir = temp.path;
  char host[256] = {};
  ASSERT_EQ(::gethostname(host, sizeof host - 1), 0);
  const fs::path target = dir / "frame.png";
  const fs::path expected_tmp = dir / ("frame.png.tmp." + std::string(host) + "." + std::to_string(::getpid()));
  bool seen = false;
  write_file_atomically(target, [&](std::ostream& out) {
    out << "data";
    seen = fs::exists(expected_tmp);
    EXPECT_FALSE(fs::exists(target));
  });
  EXPECT_TRUE(seen) << expected_tmp;
  EXPECT_FALSE(fs::exists(expected_tmp));
  std::ifstream in(target);
  std::string text;
  in >> text;
  EXPECT_EQ(text, "data");
  EXPECT_THROW(write_file_atomically(target, [](std::ostream&) { fail("writer failed"); }), Error);
  EXPECT_FALSE(fs::exists(expected_tmp));  // removed on failure; the old file stays
  EXPECT_TRUE(fs::exists(target));
}

}  // namespace
}  // namespace spume
