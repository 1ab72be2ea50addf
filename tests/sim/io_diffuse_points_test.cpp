// The renderer's read of a diffuse cache (read_diffuse_points): only positions and types are decoded,
// but the file is checked as a whole (CRC, the framing of every column, types and counts), and a
// skipped column is really skipped. io_diffuse_quantized_test.cpp checks that its particles equal the
// whole frame's on every round trip there.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "sim/io/column_codec.h"
#include "sim/io/spume_cache.h"
#include "tests/support/compact_cache_layout.h"
#include "tests/support/crc_trailer.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/spread_diffuse_frame.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;
using namespace spume;
using namespace spume::testing;

namespace {

constexpr double kStep = 0.01 / 64;

struct Written {
  TempDir dir;
  fs::path good;
  std::string bytes;
  std::vector<size_t> columns;
  size_t n;
  explicit Written(size_t count) : good(dir.path / "good.spd"), n(count) {
    write_diffuse_cache(good, spread_diffuse_frame(n), kStep);
    bytes = read_file(good);
    columns = column_starts(bytes);
  }
};

}  // namespace

TEST(DiffusePoints, ASkippedColumnIsNotDecodedButItsFramingIsChecked) {
  Written w(300'000);  // several chunks a column
  const DiffuseFrame whole = read_diffuse_cache(w.good);
  // A byte inside the velocity column's compressed chunks, the CRC made to match: the whole read
  // decodes the column and fails; the points read never looks inside it.
  std::string inside = w.bytes;
  inside[w.columns[kVelocities] + 16 + 40] ^= 0x5a;
  const fs::path edited = w.dir.write("inside.spd", with_fixed_crc(inside));
  EXPECT_NE(error_of([&] { read_diffuse_cache(edited); }).find("velocity column"), std::string::npos);
  const DiffusePoints points = read_diffuse_points(edited);
  EXPECT_TRUE(points.positions == whole.positions);
  EXPECT_TRUE(points.types == whole.types);

  // The same byte without the CRC fixed: refused before any column is read.
  const fs::path crc = w.dir.write("crc.spd", inside);
  EXPECT_NE(error_of([&] { read_diffuse_points(crc); }).find("CRC-32 mismatch"), std::string::npos);

  // Each skipped column claiming another raw size is refused, naming the file and the column.
  for (auto [column, name] : {std::pair{kVelocities, "velocity"}, {kLifetimes, "lifetime"}, {kIds, "id"}}) {
    std::string b = w.bytes;
    uint64_t raw = 0;
    std::memcpy(&raw, b.data() + w.columns[column], 8);
    raw += 2;
    std::memcpy(b.data() + w.columns[column], &raw, 8);
    const fs::path p = w.dir.write(std::string(name) + ".spd", with_fixed_crc(b));
    const std::string msg = error_of([&] { read_diffuse_points(p); });
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(std::string("the ") + name + " column holds"), std::string::npos) << msg;
  }
  // The id column claiming more stored bytes than remain.
  std::string b = w.bytes;
  const uint64_t huge = b.size();
  std::memcpy(b.data() + w.columns[kIds] + 8, &huge, 8);
  const fs::path past = w.dir.write("past.spd", with_fixed_crc(b));
  EXPECT_NE(error_of([&] { read_diffuse_points(past); }).find("the id column claims"), std::string::npos);
}

TEST(DiffusePoints, ATypeOutsideTheThreeIsRefused) {
  Written w(1000);
  // Decode the type column, set particle 5's two bits to 3, and store the column again.
  std::vector<uint8_t> types((w.n + 3) / 4);
  io::ByteReader r(std::string_view(w.bytes).substr(w.columns[kTypes], w.columns[kIds] - w.columns[kTypes]), "t");
  read_column(r, types.data(), types.size(), "type");
  types[5 / 4] |= uint8_t(3u << (2 * (5 % 4)));
  CacheBytes column;
  append_column(column, types.data(), types.size(), 1, false, column_block_bytes(w.n));
  const std::string edited = w.bytes.substr(0, w.columns[kTypes]) + std::string(column.view()) +
                             w.bytes.substr(w.columns[kIds]);
  const fs::path p = w.dir.write("type3.spd", with_fixed_crc(edited));
  const std::string msg = error_of([&] { read_diffuse_points(p); });
  EXPECT_NE(msg.find(p.string() + ": corrupt: 1 particles have a type outside 0..2"), std::string::npos) << msg;
  // The whole read refuses it too.
  EXPECT_NE(error_of([&] { read_diffuse_cache(p); }).find("type 3"), std::string::npos);
}

TEST(DiffusePoints, CountsThatDisagreeWithTheTypesAreRefused) {
  Written w(999);  // 333 of each type
  std::string b = w.bytes;
  const uint64_t counts[3] = {332, 334, 333};  // still sums to n
  std::memcpy(b.data() + 32, counts, sizeof counts);
  const fs::path p = w.dir.write("counts.spd", with_fixed_crc(b));
  const std::string msg = error_of([&] { read_diffuse_points(p); });
  EXPECT_NE(msg.find("header says 332 spray particles but the data has 333"), std::string::npos) << msg;
}
