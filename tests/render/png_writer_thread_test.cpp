// PngWriterThread (render/stage/png_writer_thread.h): each frame's PNG written while the next renders,
// one at a time, and what follows a file runs once it is on disk, in order; a failed write stops the
// next one and names its file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "render/image/png_io.h"
#include "render/stage/png_writer_thread.h"
#include "tests/support/error_of.h"
#include "tests/support/files.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

ImageRGB8 gradient(int seed) {
  ImageRGB8 img(40, 24);
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = uint8_t((i * 7 + size_t(seed) * 31) % 251);
  return img;
}

class PngWriterThreadTest : public ::testing::TestWithParam<bool> {};

TEST_P(PngWriterThreadTest, FilesAreOnDiskInOrderWhenTheirDoneRuns) {
  const testing::TempDir dir;
  PngWriterThread pngs(GetParam());
  std::vector<int> done_order;
  for (int k = 0; k < 4; ++k) {
    const fs::path path = dir.path / "frames" / ("f" + std::to_string(k) + ".png");
    pngs.write(path, gradient(k), "record " + std::to_string(k), {}, [&, k, path](double seconds) {
      done_order.push_back(k);
      EXPECT_GT(seconds, 0.0);
      // On disk, whole: the pixels and the record as given.
      EXPECT_EQ(read_png(path).rgb, gradient(k).rgb);
      EXPECT_EQ(read_png_record(path), "record " + std::to_string(k));
    });
  }
  pngs.finish();
  EXPECT_EQ(done_order, (std::vector<int>{0, 1, 2, 3}));
  // The same bytes as writing each file directly.
  write_png(dir.path / "direct.png", gradient(2), "record 2");
  EXPECT_EQ(testing::read_file(dir.path / "frames/f2.png"), testing::read_file(dir.path / "direct.png"));
}

TEST_P(PngWriterThreadTest, AFailedWriteStopsTheNextAndNamesItsFile) {
  const testing::TempDir dir;
  testing::write_file(dir.path / "blocker", "a file where a folder should be");
  const fs::path bad = dir.path / "blocker" / "f0.png", next = dir.path / "f1.png";
  PngWriterThread pngs(GetParam());
  int done = 0;
  std::string error;
  // Written in the background, the error comes with the next write; in the foreground, at once.
  error = testing::error_of([&] {
    pngs.write(bad, gradient(0), "", {}, [&](double) { ++done; });
    pngs.write(next, gradient(1), "", {}, [&](double) { ++done; });
    pngs.finish();
  });
  EXPECT_NE(error.find(bad.string()), std::string::npos) << error;
  EXPECT_EQ(done, 0);
  EXPECT_FALSE(fs::exists(next));
}

INSTANTIATE_TEST_SUITE_P(BackgroundAndNot, PngWriterThreadTest, ::testing::Bool());

}  // namespace
}  // namespace spume
