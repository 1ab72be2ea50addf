// Frame specs ("7", "0-99", "0-99:2", "1-3,5,10-20"): hand-worked selections, clipping to the
// available range, and an error that names the option, the spec and the accepted forms for each
// kind of bad input.
#include <gtest/gtest.h>

#include <climits>
#include <string>
#include <vector>

#include "sim/core/error.h"
#include "sim/core/frame_spec.h"

namespace spume {
namespace {

using Frames = std::vector<int>;

TEST(FrameSpec, SingleFrame) {
  EXPECT_EQ(parse_frame_spec("7", 0, 99, "--frames"), Frames{7});
  EXPECT_EQ(parse_frame_spec("0", 0, 99, "--frames"), Frames{0});
  EXPECT_EQ(parse_frame_spec("007", 0, 99, "--frames"), Frames{7});  // leading zeros are plain decimal
}

TEST(FrameSpec, InclusiveRange) {
  EXPECT_EQ(parse_frame_spec("0-4", 0, 99, "--frames"), (Frames{0, 1, 2, 3, 4}));
  EXPECT_EQ(parse_frame_spec("5-5", 0, 99, "--frames"), Frames{5});
}

TEST(FrameSpec, SteppedRangeStartsAtItsStartAndStopsAtOrBeforeItsEnd) {
  EXPECT_EQ(parse_frame_spec("0-9:3", 0, 99, "--frames"), (Frames{0, 3, 6, 9}));
  EXPECT_EQ(parse_frame_spec("0-10:4", 0, 99, "--frames"), (Frames{0, 4, 8}));
  EXPECT_EQ(parse_frame_spec("3-4:10", 0, 99, "--frames"), Frames{3});
  EXPECT_EQ(parse_frame_spec("1-7:1", 0, 99, "--frames"), (Frames{1, 2, 3, 4, 5, 6, 7}));
}

TEST(FrameSpec, ListIsSortedAndUnique) {
  EXPECT_EQ(parse_frame_spec("1-3,5,10-12", 0, 99, "--frames"), (Frames{1, 2, 3, 5, 10, 11, 12}));
  EXPECT_EQ(parse_frame_spec("10-12,1-3,2,11", 0, 99, "--frames"), (Frames{1, 2, 3, 10, 11, 12}));
  EXPECT_EQ(parse_frame_spec("0-8:4,2-6:2", 0, 99, "--frames"), (Frames{0, 2, 4, 6, 8}));
}

TEST(FrameSpec, ChunkOvershootingTheEndSelectsWhatRemains) {
  EXPECT_EQ(parse_frame_spec("95-104", 0, 99, "--frames"), (Frames{95, 96, 97, 98, 99}));
  EXPECT_EQ(parse_frame_spec("0-5", 3, 10, "--frames"), (Frames{3, 4, 5}));
  EXPECT_EQ(parse_frame_spec("5,200", 0, 99, "--frames"), Frames{5});
  EXPECT_EQ(parse_frame_spec("0-1000000", 1, 3, "--frames"), (Frames{1, 2, 3}));
}

TEST(FrameSpec, ClippedSteppedRangeKeepsItsPhase) {
  EXPECT_EQ(parse_frame_spec("0-10:4", 1, 10, "--frames"), (Frames{4, 8}));
  EXPECT_EQ(parse_frame_spec("1-20:5", 7, 20, "--frames"), (Frames{11, 16}));
  EXPECT_EQ(parse_frame_spec("0-99:2", 96, 99, "--frames"), (Frames{96, 98}));
}

TEST(FrameSpec, LargestIntFramesDoNotOverflow) {
  // 2147483640 + 5 = 2147483645, and one more step would pass INT_MAX.
  EXPECT_EQ(parse_frame_spec("2147483640-2147483647:5", 0, INT_MAX, "--frames"), (Frames{2147483640, 2147483645}));
  EXPECT_EQ(parse_frame_spec("2147483647", 0, INT_MAX, "--frames"), Frames{INT_MAX});
  EXPECT_EQ(parse_frame_spec("2147483646-2147483647", 0, INT_MAX, "--frames"), (Frames{2147483646, 2147483647}));
}

// Expects an Error whose message holds every one of `parts`.
void expect_error(const std::string& spec, int first, int last, const std::vector<std::string>& parts,
                  const char* what = "--frames") {
  try {
    const Frames f = parse_frame_spec(spec, first, last, what);
    ADD_FAILURE() << "\"" << spec << "\" was accepted, giving " << f.size() << " frames";
  } catch (const Error& e) {
    const std::string msg = e.what();
    for (const std::string& part : parts)
      EXPECT_NE(msg.find(part), std::string::npos) << "\"" << spec << "\": message lacks \"" << part << "\": " << msg;
  }
}

const std::string kForms = "N, A-B, A-B:STEP";

TEST(FrameSpec, MalformedSpecsNameTheOptionTheValueAndTheAcceptedForms) {
  expect_error("", 0, 99, {"--frames", "empty", kForms});
  expect_error("abc", 0, 99, {"--frames", "\"abc\"", kForms});
  expect_error("1-x", 0, 99, {"--frames", "\"1-x\"", "end", kForms});
  expect_error("x-3", 0, 99, {"\"x-3\"", "start", kForms});
  expect_error("1-3-5", 0, 99, {"\"1-3-5\"", kForms});
  expect_error("+5", 0, 99, {"\"+5\"", kForms});
  expect_error("0x10", 0, 99, {"\"0x10\"", kForms});
  expect_error("1.5", 0, 99, {"\"1.5\"", kForms});
  expect_error("1-", 0, 99, {"\"1-\"", "no end", kForms});
  expect_error("0-9:", 0, 99, {"\"0-9:\"", "no step", kForms});
  expect_error("5:2", 0, 99, {"\"5:2\"", "no range", kForms});
  expect_error("1:2-3", 0, 99, {"\"1:2-3\"", "step before the range", kForms});
  expect_error("0-9:x", 0, 99, {"\"0-9:x\"", "step", kForms});
}

TEST(FrameSpec, ListItemErrorsQuoteTheItemAndTheWholeSpec) {
  expect_error("1-3,5-x,7", 0, 99, {"--frames", "item \"5-x\"", "\"1-3,5-x,7\"", kForms});
  expect_error("1,,2", 0, 99, {"\"1,,2\"", "empty item", kForms});
  expect_error("1,", 0, 99, {"\"1,\"", "empty item"});
  expect_error(",1", 0, 99, {"\",1\"", "empty item"});
}

TEST(FrameSpec, WhiteSpaceIsRejected) {
  expect_error("1 - 3", 0, 99, {"\"1 - 3\"", "white space", kForms});
  expect_error("1, 2", 0, 99, {"\" 2\"", "white space"});
  expect_error(" 7", 0, 99, {"white space"});
}

TEST(FrameSpec, NegativeFramesAreRejected) {
  expect_error("-5", 0, 99, {"\"-5\"", "negative", kForms});
  expect_error("-5-3", 0, 99, {"negative"});
  expect_error("3--5", 0, 99, {"\"3--5\"", "negative"});
}

TEST(FrameSpec, ReversedRangeIsAnError) {
  expect_error("5-3", 0, 99, {"--frames", "\"5-3\"", "ends (3) before it starts (5)"});
  expect_error("9-0:2", 0, 99, {"\"9-0:2\"", "before it starts"});
}

TEST(FrameSpec, ZeroStepIsAnError) {
  expect_error("0-9:0", 0, 99, {"--frames", "\"0-9:0\"", "step 0", "at least 1"});
  expect_error("0-9:000", 0, 99, {"step 0"});
}

TEST(FrameSpec, NumbersBeyondIntAreErrors) {
  expect_error("2147483648", 0, INT_MAX, {"\"2147483648\"", "2147483647"});
  expect_error("99999999999", 0, 99, {"\"99999999999\"", "larger than the largest allowed"});
  expect_error("1-99999999999", 0, 99, {"end 99999999999", "larger"});
  expect_error("0-9:99999999999", 0, 99, {"step 99999999999", "larger"});
}

TEST(FrameSpec, SpecWhollyOutsideTheRangeNamesSpecAndRange) {
  expect_error("200-300", 0, 99, {"--frames", "\"200-300\"", "no frame", "0-99"});
  expect_error("0-2", 5, 10, {"\"0-2\"", "5-10"});
  // Overlapping the range is not enough: the stepped frames 0 and 50 both miss [1, 49].
  expect_error("0-99:50", 1, 49, {"\"0-99:50\"", "no frame", "1-49"});
}

TEST(FrameSpec, EmptyAvailableRangeIsAnError) { expect_error("1", 5, 4, {"--frames", "5-4", "empty"}); }

TEST(FrameSpec, ErrorsNameTheCallersOption) {
  expect_error("5-3", 0, 99, {"farm --frames"}, "farm --frames");
  expect_error("x", 0, 99, {"render.frames"}, "render.frames");
}

}  // namespace
}  // namespace spume
