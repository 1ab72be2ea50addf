// OpenEXR files (image/exr_io.h): values come back as the half or float the file holds, header strings
// come back, and bad paths or files give errors naming them.
#include <gtest/gtest.h>

#include <fstream>

#include "render/image/exr_io.h"
#include "sim/core/error.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

// 3 x 2 pixels of interleaved (a, b) pairs: a is written as HALF, b as FLOAT.
TEST(ExrIo, HalfChannelsRoundToNearestAndFloatChannelsAreExact) {
  const testing::TempDir temp("exr_io");
  const std::vector<float> ab = {0.1f, 0.1f, 1.0f, 3.0f, -2.5f, 1e-3f, 65504.0f, 1e10f, 1.0f / 3.0f, 7.0f, 0.0f, -1.0f};
  const fs::path path = temp.path / "sub" / "six.exr";
  fs::create_directories(path.parent_path());
  write_exr(path, 3, 2, {{"layer.a", ab.data(), 2}, {"b", ab.data() + 1, 2, true}}, {{"note", "six pixels"}});
  const ExrContents c = read_exr(path);
  EXPECT_EQ(c.width, 3);
  EXPECT_EQ(c.height, 2);
  EXPECT_EQ(c.compression, "zip");
  EXPECT_EQ(c.strings.at("note"), "six pixels");
  EXPECT_FALSE(c.full_float.at("layer.a"));
  EXPECT_TRUE(c.full_float.at("b"));
  // Halves by hand: 0.1 = 1.6 * 2^-4 -> mantissa round(0.6 * 1024) = 614 -> 1638/16384; 1/3 ->
  // 1.3333 * 2^-2 -> 341/1024 rounds to 1365/4096; -2.5 and 65504 (the largest half) are exact.
  const std::vector<float> a = c.channels.at("layer.a"), b = c.channels.at("b");
  EXPECT_EQ(a[0], 1638.0f / 16384.0f);
  EXPECT_EQ(a[1], 1.0f);
  EXPECT_EQ(a[2], -2.5f);
  EXPECT_EQ(a[3], 65504.0f);
  EXPECT_EQ(a[4], 1365.0f / 4096.0f);
  EXPECT_EQ(a[5], 0.0f);
  EXPECT_EQ(b, (std::vector<float>{0.1f, 3.0f, 1e-3f, 1e10f, 7.0f, -1.0f}));
  EXPECT_EQ(read_exr_string(path, "note"), "six pixels");
  EXPECT_EQ(read_exr_string(path, "missing"), std::nullopt);
  // Written atomically: nothing but the file is left in the folder.
  EXPECT_EQ(std::distance(fs::directory_iterator(path.parent_path()), fs::directory_iterator()), 1);
}

// An interleaved RGBA layer (converted four channels at a time) comes back channel by channel.
TEST(ExrIo, InterleavedRgbaLayersComeBackChannelByChannel) {
  const testing::TempDir temp("exr_io_rgba");
  std::vector<float> rgba(5 * 3 * 4);
  for (size_t i = 0; i < rgba.size(); ++i) rgba[i] = float(i) * 0.25f - 3.0f;  // exact in half
  const fs::path path = temp.path / "rgba.exr";
  std::vector<ExrChannel> channels;
  for (int c = 0; c < 4; ++c) channels.push_back({std::string("L.") + "RGBA"[c], rgba.data() + c, 4});
  write_exr(path, 5, 3, channels, {});
  const ExrContents back = read_exr(path);
  for (int c = 0; c < 4; ++c) {
    const std::vector<float>& v = back.channels.at(std::string("L.") + "RGBA"[c]);
    for (size_t p = 0; p < 15; ++p) ASSERT_EQ(v[p], rgba[4 * p + size_t(c)]) << "channel " << c << " pixel " << p;
  }
}

TEST(ExrIo, ErrorsNameTheFile) {
  const testing::TempDir temp("exr_io_errors");
  const float v[1] = {1.0f};
  const fs::path blocked = temp.path / "a_file";
  std::ofstream(blocked) << "x";
  try {
    write_exr(blocked / "frame.exr", 1, 1, {{"R", v, 1}}, {});
    FAIL() << "writing under a file should fail";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("frame.exr"), std::string::npos) << e.what();
  }
  const fs::path bad = temp.path / "not_an_exr.exr";
  std::ofstream(bad) << "this is not an OpenEXR file at all";
  try {
    read_exr(bad);
    FAIL() << "a text file is not an EXR";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not_an_exr.exr"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_exr_string(bad, "spume/record"), std::nullopt);
  EXPECT_EQ(read_exr_string(temp.path / "absent.exr", "spume/record"), std::nullopt);
  EXPECT_THROW(write_exr(temp.path / "empty.exr", 0, 4, {}, {}), Error);
}

}  // namespace
}  // namespace spume
