// llvmpipe thread count vs output bytes. Mesa reads LP_NUM_THREADS once per process (when the first
// context is created), so each setting runs in a child process (tests/render/gl_child), which writes
// the raw float buffers for this test to compare.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "tests/support/files.h"
#include "tests/support/run_command.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

// Runs the child program (tests/render/gl_child) with LP_NUM_THREADS set; its output, or "" on failure.
std::string run_child(const std::string& lp_threads) {
  const testing::TempDir temp("gl_child_" + lp_threads);
  const auto path = temp / "child.bin";
  const std::string cmd = "LP_NUM_THREADS=" + lp_threads + " " + SPUME_GL_CHILD + " " + path.string() +
                          " > /dev/null 2>&1";
  if (testing::run_command(cmd).status != 0) return {};
  return testing::read_file(path);
}

TEST(GlDeterminism, SameBytesForAnyLlvmpipeThreadCount) {
  const std::string zero = run_child("0"), two = run_child("2"), four = run_child("4");
  ASSERT_GT(zero.size(), sizeof(size_t)) << "child render failed";
  ASSERT_EQ(zero.size(), two.size());
  ASSERT_EQ(zero.size(), four.size());
  size_t threads[3];
  std::memcpy(&threads[0], zero.data(), sizeof(size_t));
  std::memcpy(&threads[1], two.data(), sizeof(size_t));
  std::memcpy(&threads[2], four.data(), sizeof(size_t));
  std::printf("llvmpipe threads started: LP_NUM_THREADS=0 -> %zu, 2 -> %zu, 4 -> %zu\n", threads[0], threads[1],
              threads[2]);
  EXPECT_LT(threads[0], threads[2]) << "LP_NUM_THREADS had no effect";
  EXPECT_TRUE(zero.compare(sizeof(size_t), std::string::npos, two, sizeof(size_t)) == 0) << "0 vs 2 threads";
  EXPECT_TRUE(zero.compare(sizeof(size_t), std::string::npos, four, sizeof(size_t)) == 0) << "0 vs 4 threads";
}

}  // namespace
}  // namespace spume
