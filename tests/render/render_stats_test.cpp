// OUT/<scene>/render_stats.csv: rows merge by frame, so a farm's chunks and a re-render of one frame
// each leave every other frame's row in place.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include "render/stage/render_stats.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

class RenderStats : public ::testing::Test {
 protected:
  const testing::TempDir temp_;
  const std::filesystem::path& dir_ = temp_.path;
};

constexpr const char* kHeader =
    "frame,triangles,diffuse_spheres,load_ms,reconstruct_ms,surface_ms,volume_ms,composite_ms,write_ms,total_ms\n";

TEST_F(RenderStats, RowsMergeByFrameAndStaySorted) {
  merge_render_stats(dir_, {{.frame = 2, .triangles = 10, .spheres = 5, .total = 0.25},
                            {.frame = 0, .triangles = 7, .spheres = 1, .volume = 0.0125, .total = 0.5}});
  merge_render_stats(dir_, {{.frame = 1, .surface = 0.002}});
  // Frame 2 drawn again: its row is replaced; 0 and 1 stay.
  merge_render_stats(dir_, {{.frame = 2, .triangles = 11, .spheres = 6, .load = 0.1, .total = 1.0}});
  EXPECT_EQ(read_text(dir_ / "render_stats.csv"), std::string(kHeader) +
                                                      "0,7,1,0.0,0.0,0.0,12.5,0.0,0.0,500.0\n"
                                                      "1,0,0,0.0,0.0,2.0,0.0,0.0,0.0,0.0\n"
                                                      "2,11,6,100.0,0.0,0.0,0.0,0.0,0.0,1000.0\n");
}

TEST_F(RenderStats, AFileOfAnotherFormatIsReplaced) {
  std::ofstream(dir_ / "render_stats.csv") << "frame,ms\n0,12\n1,13\n";
  merge_render_stats(dir_, {{.frame = 4, .total = 0.003}});
  EXPECT_EQ(read_text(dir_ / "render_stats.csv"), std::string(kHeader) + "4,0,0,0.0,0.0,0.0,0.0,0.0,0.0,3.0\n");
}

TEST_F(RenderStats, NothingDrawnLeavesNoFile) {
  merge_render_stats(dir_, {});
  EXPECT_FALSE(std::filesystem::exists(dir_ / "render_stats.csv"));
}

}  // namespace
}  // namespace spume
