// Farm chunks: frame sets written back as specs (hand-worked cases and a round trip through the
// parser), selection clamped to the scene's frames, and chunking that covers every frame once.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "sim/core/error.h"
#include "sim/core/frame_spec.h"
#include "render/app/farm/farm_plan.h"
#include "tests/support/error_of.h"

namespace spume::farm {
namespace {

using testing::error_of;
using Frames = std::vector<int>;

Frames range(int a, int b, int step = 1) {
  Frames f;
  for (int i = a; i <= b; i += step) f.push_back(i);
  return f;
}

TEST(FormatFrameSpec, HandWorkedSets) {
  EXPECT_EQ(format_frame_spec({}), "");
  EXPECT_EQ(format_frame_spec({7}), "7");
  EXPECT_EQ(format_frame_spec(range(0, 9)), "0-9");
  EXPECT_EQ(format_frame_spec({3, 4}), "3-4");
  EXPECT_EQ(format_frame_spec({1, 5}), "1,5");  // a stepped pair reads better as a list
  EXPECT_EQ(format_frame_spec(range(0, 18, 2)), "0-18:2");
  EXPECT_EQ(format_frame_spec({1, 2, 3, 5, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20}), "1-3,5,10-20");
  EXPECT_EQ(format_frame_spec({0, 1, 2, 4, 6, 8}), "0-2,4-8:2");
}

TEST(FormatFrameSpec, ParsesBackToTheSameFrames) {
  std::mt19937 random(12345);
  for (int trial = 0; trial < 500; ++trial) {
    Frames frames;
    const int density = 1 + int(random() % 4);
    for (int f = 0; f < 200; ++f)
      if (random() % density == 0) frames.push_back(f);
    if (frames.empty()) continue;
    const std::string spec = format_frame_spec(frames);
    EXPECT_EQ(parse_frame_spec(spec, 0, 1000, "--frames"), frames) << spec;
  }
}

TEST(SelectFrames, ClampsAChunkThatOvershootsTheEnd) {
  EXPECT_EQ(select_frames("5-99", range(0, 7)), (Frames{5, 6, 7}));
  EXPECT_EQ(select_frames("0-99:2", range(3, 9)), (Frames{4, 6, 8}));
}

TEST(SelectFrames, KeepsOnlyFramesTheSceneHas) {
  EXPECT_EQ(select_frames("0-10", {1, 2, 5, 9}), (Frames{1, 2, 5, 9}));
  EXPECT_EQ(select_frames("1-3,5,10-20", range(0, 12)), (Frames{1, 2, 3, 5, 10, 11, 12}));
}

TEST(SelectFrames, ErrorsNameTheOptionAndTheSpec) {
  const std::string none = error_of([] { select_frames("3-4", {1, 2, 5, 9}); });
  EXPECT_NE(none.find("--frames"), std::string::npos) << none;
  EXPECT_NE(none.find("3-4"), std::string::npos) << none;
  const std::string malformed = error_of([] { select_frames("1-x", range(0, 9)); });
  EXPECT_NE(malformed.find("--frames"), std::string::npos) << malformed;
  EXPECT_NE(malformed.find("accepted forms"), std::string::npos) << malformed;
  EXPECT_NE(error_of([] { select_frames("1", {}); }).find("no frames"), std::string::npos);
}

TEST(ChunkSpecs, ConsecutiveGroupsWithAShorterLastOne) {
  EXPECT_EQ(chunk_specs(range(0, 7), 3), (std::vector<std::string>{"0-2", "3-5", "6-7"}));
  EXPECT_EQ(chunk_specs(range(0, 7), 1), (std::vector<std::string>{"0", "1", "2", "3", "4", "5", "6", "7"}));
  EXPECT_EQ(chunk_specs(range(0, 7), 100), (std::vector<std::string>{"0-7"}));
  EXPECT_EQ(chunk_specs(range(0, 20, 2), 4), (std::vector<std::string>{"0-6:2", "8-14:2", "16-20:2"}));
  EXPECT_EQ(chunk_specs({1, 2, 3, 5, 10, 11}, 4), (std::vector<std::string>{"1-3,5", "10-11"}));
}

TEST(ChunkSpecs, CoverEveryFrameExactlyOnce) {
  const Frames frames = select_frames("1-3,5,10-200:3,250-251", range(0, 300));
  for (int chunk : {1, 2, 5, 7, 64, 1000}) {
    const std::vector<std::string> chunks = chunk_specs(frames, chunk);
    EXPECT_EQ(chunks.size(), (frames.size() + size_t(chunk) - 1) / size_t(chunk));
    Frames covered;
    for (const std::string& spec : chunks) {
      const Frames part = parse_frame_spec(spec, 0, 300, "--frames");
      EXPECT_LE(part.size(), size_t(chunk)) << spec;
      covered.insert(covered.end(), part.begin(), part.end());
    }
    EXPECT_EQ(covered, frames) << "chunk " << chunk;
  }
}

TEST(ChunkSpecs, ChunkBelowOneNamesTheOption) {
  const std::string e = error_of([] { chunk_specs(range(0, 7), 0); });
  EXPECT_NE(e.find("--chunk"), std::string::npos) << e;
}

}  // namespace
}  // namespace spume::farm
