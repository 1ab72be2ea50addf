// PNG writing and reading: round trip, atomic write, and errors that name the file.
#include <gtest/gtest.h>
#include <png.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "sim/core/error.h"
#include "render/image/png_io.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

fs::path test_dir(const std::string& name) {
  const fs::path dir = fs::path(SPUME_OUT_DIR) / "tests" / "image_png" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

ImageRGB8 random_image(int w, int h, unsigned seed) {
  ImageRGB8 img(w, h);
  std::mt19937 rng(seed);
  for (uint8_t& b : img.rgb) b = uint8_t(rng() & 0xFF);
  return img;
}

std::vector<uint8_t> read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& p, const std::vector<uint8_t>& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// Expects read_png(p) to throw an Error whose message names p and contains `what`.
void expect_error_naming(const fs::path& p, const std::string& what) {
  try {
    read_png(p);
    FAIL() << "no error for " << p;
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  }
}

TEST(PngIo, RoundTripIsExact) {
  const fs::path dir = test_dir("round_trip");
  for (auto [w, h] : {std::pair{1, 1}, std::pair{37, 23}, std::pair{160, 90}}) {
    const ImageRGB8 img = random_image(w, h, unsigned(w * 1000 + h));
    const fs::path p = dir / ("img_" + std::to_string(w) + ".png");
    write_png(p, img);
    const ImageRGB8 back = read_png(p);
    ASSERT_EQ(back.width, w);
    ASSERT_EQ(back.height, h);
    EXPECT_EQ(back.rgb, img.rgb);
  }
}

TEST(PngIo, WriteIsAtomicAndCreatesDirectories) {
  const fs::path dir = test_dir("atomic");
  const fs::path p = dir / "a" / "b" / "frame.png";
  write_png(p, random_image(8, 8, 1));
  write_png(p, random_image(8, 8, 2));  // overwrite in place
  EXPECT_EQ(read_png(p).rgb, random_image(8, 8, 2).rgb);
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(p.parent_path())) files += entry.is_regular_file();
  EXPECT_EQ(files, 1u) << "a temporary file was left behind";
}

TEST(PngIo, TheFramesRecordTravelsWithItsPixels) {
  const fs::path dir = test_dir("record");
  const fs::path with = dir / "with.png", without = dir / "without.png";
  const std::string record = R"({"render":{"alpha":60},"diffuse":[123,0,3735928559]})";
  write_png(with, random_image(20, 10, 3), record);
  write_png(without, random_image(20, 10, 3));
  EXPECT_EQ(read_png_record(with), record);
  EXPECT_EQ(read_png(with).rgb, random_image(20, 10, 3).rgb);  // pixels unchanged by the text
  EXPECT_FALSE(read_png_record(without));
  EXPECT_FALSE(read_png_record(dir / "missing.png"));
  write_bytes(dir / "not.png", {1, 2, 3});
  EXPECT_FALSE(read_png_record(dir / "not.png"));
  // Cut inside the text chunk: no record, no crash.
  std::vector<uint8_t> bytes = read_bytes(with);
  bytes.resize(60);
  write_bytes(dir / "cut.png", bytes);
  EXPECT_FALSE(read_png_record(dir / "cut.png"));
}

TEST(PngIo, ReadsRgbaDroppingAlpha) {
  const fs::path dir = test_dir("rgba");
  std::vector<uint8_t> rgba = {10, 20, 30, 0, 200, 150, 100, 255, 1, 2, 3, 128, 4, 5, 6, 7};
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = 2, image.height = 2, image.format = PNG_FORMAT_RGBA;
  png_alloc_size_t size = 0;
  ASSERT_TRUE(png_image_write_to_memory(&image, nullptr, &size, 0, rgba.data(), 0, nullptr));
  std::vector<uint8_t> bytes(size);
  ASSERT_TRUE(png_image_write_to_memory(&image, bytes.data(), &size, 0, rgba.data(), 0, nullptr));
  bytes.resize(size);
  write_bytes(dir / "rgba.png", bytes);
  const ImageRGB8 img = read_png(dir / "rgba.png");
  ASSERT_EQ(img.width, 2);
  EXPECT_EQ(img.rgb, (std::vector<uint8_t>{10, 20, 30, 200, 150, 100, 1, 2, 3, 4, 5, 6}));
}

TEST(PngIo, CorruptFileErrorNamesTheFile) {
  const fs::path dir = test_dir("corrupt");
  const fs::path good = dir / "good.png";
  write_png(good, random_image(64, 64, 3));
  std::vector<uint8_t> bytes = read_bytes(good);

  std::vector<uint8_t> truncated(bytes.begin(), bytes.begin() + std::ptrdiff_t(bytes.size() / 2));
  write_bytes(dir / "truncated.png", truncated);
  expect_error_naming(dir / "truncated.png", "corrupt PNG");

  std::vector<uint8_t> flipped = bytes;
  for (size_t i = 60; i < flipped.size() - 20; i += 7) flipped[i] ^= 0x5A;  // inside IDAT: CRC/zlib errors
  write_bytes(dir / "flipped.png", flipped);
  expect_error_naming(dir / "flipped.png", "corrupt PNG");

  write_bytes(dir / "text.png", {'h', 'e', 'l', 'l', 'o', ' ', 'w', 'o', 'r', 'l', 'd'});
  expect_error_naming(dir / "text.png", "not a PNG");

  expect_error_naming(dir / "missing.png", "cannot open");
}

TEST(PngIo, HeaderClaimingMoreThanTheFileHoldsIsRefusedBeforeAllocating) {
  // A 64x64 file whose header is rewritten to 60000x60000 (with a valid CRC): decoding would fill
  // 10 GB before finding the data short, so the size is checked against the file first.
  const fs::path dir = test_dir("huge_claim");
  write_png(dir / "small.png", random_image(64, 64, 7));
  std::vector<uint8_t> bytes = read_bytes(dir / "small.png");
  auto put32 = [&](size_t at, uint32_t v) {
    for (int k = 0; k < 4; ++k) bytes[at + size_t(k)] = uint8_t(v >> (24 - 8 * k));
  };
  put32(16, 60000), put32(20, 60000);       // IHDR width, height (after signature, length, type)
  put32(29, uint32_t(crc32(0, bytes.data() + 12, 17)));  // CRC over the type and 13 data bytes
  write_bytes(dir / "huge.png", bytes);
  expect_error_naming(dir / "huge.png", "needs more data than the file holds");
}

}  // namespace
}  // namespace spume
