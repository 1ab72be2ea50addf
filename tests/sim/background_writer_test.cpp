// BackgroundWriter (io/background_writer.h): files written on its thread arrive whole and in place,
// one at a time; a failed write is reported by the next call, naming the file; nothing is left behind
// half-written; the destructor waits for the file in flight; the bytes' memory goes back to the pool
// once their file is written, not when the next file is started. And the pipeline's encode-then-write
// gives the bytes write_diffuse_cache writes.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <random>
#include <string>
#include <thread>

#include "sim/io/background_writer.h"
#include "sim/io/spume_cache.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

CacheBytes bytes_of(const std::string& text) {
  CacheBytes b;
  b.append(text.data(), text.size());
  return b;
}

TEST(BackgroundWriter, WritesEachFileWholeAndInPlace) {
  testing::TempDir dir;
  const std::string big(3'000'000, 'x'), small = "second";
  {
    BackgroundWriter writer;
    writer.write(dir / "a.bin", bytes_of(big));
    writer.write(dir / "sub" / "b.bin", bytes_of(small));  // waits for a.bin first
    EXPECT_EQ(testing::read_file(dir / "a.bin"), big);    // the first is in place once the second starts
    writer.wait();
    EXPECT_EQ(testing::read_file(dir / "sub" / "b.bin"), small);
    writer.write(dir / "c.bin", bytes_of(big));
  }  // the destructor waits
  EXPECT_EQ(testing::read_file(dir / "c.bin"), big);
  // Only the three files: no temporaries left.
  size_t files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path)) files += e.is_regular_file();
  EXPECT_EQ(files, 3u);
}

TEST(BackgroundWriter, AFailedWriteIsReportedByTheNextCallNamingTheFile) {
  testing::TempDir dir;
  const std::filesystem::path blocker = dir.write("blocker", "a file where a folder should be");
  BackgroundWriter writer;
  writer.write(blocker / "frame.spd", bytes_of("data"));
  const std::string message = testing::error_of([&] { writer.write(dir / "next.spd", bytes_of("next")); });
  EXPECT_NE(message.find("frame.spd"), std::string::npos) << message;
  // The call that reported it did not start its own file; the error is given once, and the writer
  // carries on with the next file.
  EXPECT_FALSE(std::filesystem::exists(dir / "next.spd"));
  writer.wait();
  writer.write(dir / "next.spd", bytes_of("next"));
  writer.wait();
  EXPECT_EQ(testing::read_file(dir / "next.spd"), "next");
  writer.write(blocker / "again.spd", bytes_of("data"));
  EXPECT_NE(testing::error_of([&] { writer.wait(); }).find("again.spd"), std::string::npos);
}

TEST(BackgroundWriter, TheBytesMemoryGoesBackToThePoolOnceTheirFileIsWritten) {
  // The next frame's encoding, which runs before the next write(), is what wants that memory.
  testing::TempDir dir;
  CacheBytes bytes;
  bytes.resize(64 << 20);
  std::fill_n(bytes.data(), bytes.size(), 'z');
  const size_t kept_before = scratch_pool_kept_bytes();
  BackgroundWriter writer;
  writer.write(dir / "frame.spd", std::move(bytes));
  // Not wait(): that ends the task and would free the bytes either way.
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (scratch_pool_kept_bytes() < kept_before + (64 << 20) && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(scratch_pool_kept_bytes(), kept_before + (64 << 20));
  writer.wait();
  EXPECT_EQ(std::filesystem::file_size(dir / "frame.spd"), size_t(64) << 20);
}

TEST(BackgroundWriter, EncodeThenWriteGivesWhatWriteDiffuseCacheWrites) {
  testing::TempDir dir;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  DiffuseFrame frame;
  frame.index = 7, frame.time = 0.28;
  frame.resize(5000);
  for (size_t i = 0; i < frame.size(); ++i) {
    frame.ids[i] = diffuse_id(uint32_t(i), 3, 0);
    frame.positions[i] = Vec3f(u(rng), u(rng), u(rng));
    frame.velocities[i] = Vec3f(u(rng), u(rng), u(rng));
    frame.lifetimes[i] = 1.0f + u(rng);
    frame.types[i] = DiffuseType(i % 3);
  }
  for (double step : {0.0, 1e-4}) {
    write_diffuse_cache(dir / "direct.spd", frame, step);
    BackgroundWriter writer;
    writer.write(dir / "background.spd", encode_diffuse_cache(frame, step, "background.spd"));
    writer.wait();
    EXPECT_EQ(testing::read_file(dir / "background.spd"), testing::read_file(dir / "direct.spd")) << step;
  }
}

}  // namespace
}  // namespace spume
