// Large files past the page cache (core/direct_io.h, and write_bytes_atomically in core/atomic_file.h):
// the bytes arrive whole whatever their alignment and size, their whole 4 KiB blocks bypass the
// page cache both ways (checked against the kernel's account, mincore), and failures name the file.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "sim/core/atomic_file.h"
#include "sim/core/direct_io.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

// `size` random bytes (and one more) at a 4 KiB-aligned address.
struct AlignedBytes {
  explicit AlignedBytes(size_t n, unsigned seed = 11)
      : data(static_cast<char*>(std::aligned_alloc(4096, (n + 4096) / 4096 * 4096))), size(n) {
    std::mt19937 rng(seed);
    for (size_t i = 0; i < n + 1; ++i) data[i] = char(rng());
  }
  ~AlignedBytes() { std::free(data); }
  AlignedBytes(const AlignedBytes&) = delete;
  AlignedBytes& operator=(const AlignedBytes&) = delete;
  char* data;
  size_t size;
};

// Whether the file system in `dir` takes a direct write of one aligned block (some refuse the open,
// some only the write).
bool direct_io_here(const fs::path& dir) {
  const fs::path probe = dir / "probe";
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_DIRECT, 0666);
  if (fd < 0) return false;
  const AlignedBytes block(4096);
  const bool wrote = ::write(fd, block.data, 4096) == 4096;
  ::close(fd);
  fs::remove(probe);
  return wrote;
}

// Which of the file's first `pages` 4 KiB pages the page cache holds (a mapping that touches none).
std::vector<bool> cached_pages(const fs::path& file, size_t pages) {
  const int fd = ::open(file.c_str(), O_RDONLY);
  EXPECT_GE(fd, 0);
  void* map = ::mmap(nullptr, pages * 4096, PROT_READ, MAP_SHARED, fd, 0);
  EXPECT_NE(map, MAP_FAILED);
  std::vector<unsigned char> flags(pages);
  EXPECT_EQ(::mincore(map, pages * 4096, flags.data()), 0);
  ::munmap(map, pages * 4096);
  ::close(fd);
  std::vector<bool> out(pages);
  for (size_t p = 0; p < pages; ++p) out[p] = flags[p] & 1;
  return out;
}

const size_t kSizes[] = {0, 100, 4096, 3 * 4096, 3 * 4096 + 123};

TEST(DirectIo, WrittenBytesArriveWholeWhateverTheirAlignmentAndSize) {
  const testing::TempDir temp;
  const AlignedBytes bytes(3 * 4096 + 123);
  for (size_t size : kSizes)
    for (size_t shift : {0, 1}) {  // 4 KiB aligned (direct blocks, then the tail) or not (all buffered)
      const fs::path target = temp.path / ("out_" + std::to_string(size) + "_" + std::to_string(shift) + ".bin");
      write_bytes_atomically(target, bytes.data + shift, size);
      EXPECT_EQ(testing::read_file(target), std::string(bytes.data + shift, size)) << target;
    }
  size_t files = 0;
  for (const auto& e : fs::directory_iterator(temp.path)) files += e.is_regular_file();
  EXPECT_EQ(files, 10u);  // no temporaries left behind
  const fs::path blocker = temp.path / "blocker";
  write_bytes_atomically(blocker, bytes.data, 10);
  const std::string message = testing::error_of([&] { write_bytes_atomically(blocker / "frame.spd", bytes.data, 10); });
  EXPECT_NE(message.find("frame.spd"), std::string::npos) << message;
}

TEST(DirectIo, ReadBytesArriveWholeWhateverTheirAlignmentAndSize) {
  const testing::TempDir temp;
  const AlignedBytes file_bytes(3 * 4096 + 123, 5);
  for (size_t size : kSizes)
    for (size_t shift : {0, 1}) {
      const fs::path file = temp.path / ("in_" + std::to_string(size) + ".bin");
      testing::write_file(file, std::string(file_bytes.data, size));
      AlignedBytes into(size + 1, 7);
      read_file_bytes(file, into.data + shift, size);
      EXPECT_EQ(std::string(into.data + shift, size), std::string(file_bytes.data, size)) << size << " " << shift;
    }
  AlignedBytes into(3 * 4096 + 124);
  const std::string missing = testing::error_of([&] { read_file_bytes(temp.path / "none.spd", into.data, 10); });
  EXPECT_NE(missing.find("none.spd"), std::string::npos) << missing;
  // A file shorter than asked (changed since its size was taken), in the direct part and in the tail.
  struct Shorter {
    std::string name;
    size_t asked;
  };
  for (const Shorter& file : {Shorter{"in_100.bin", 4096 + 50}, Shorter{"in_12288.bin", 3 * 4096 + 123}}) {
    const std::string shorter = testing::error_of([&] { read_file_bytes(temp.path / file.name, into.data, file.asked); });
    EXPECT_NE(shorter.find(file.name), std::string::npos) << shorter;
    EXPECT_NE(shorter.find("file changed"), std::string::npos) << shorter;
  }
}

TEST(DirectIo, AlignedBlocksBypassThePageCacheBothWays) {
  const testing::TempDir temp;
  if (!direct_io_here(temp.path)) GTEST_SKIP() << "this file system refuses direct I/O; reads and writes use the page cache";
  const size_t pages = 16;
  const AlignedBytes bytes(pages * 4096 + 100);
  const fs::path target = temp.path / "cache.spd";
  write_bytes_atomically(target, bytes.data, bytes.size);
  for (size_t p = 0; p < pages; ++p) EXPECT_FALSE(cached_pages(target, pages)[p]) << "written page " << p;
  AlignedBytes back(bytes.size);
  read_file_bytes(target, back.data, bytes.size);
  EXPECT_EQ(std::string(back.data, back.size), std::string(bytes.data, bytes.size));
  for (size_t p = 0; p < pages; ++p) EXPECT_FALSE(cached_pages(target, pages)[p]) << "read page " << p;
}

}  // namespace
}  // namespace spume
