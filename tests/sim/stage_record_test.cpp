// What a stage's outputs were made from (io/stage_record.h): records compared case by case.
#include <gtest/gtest.h>

#include <filesystem>

#include "sim/core/error.h"
#include "sim/io/stage_record.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

using Json = nlohmann::json;

StageRecord record(int first, int last) {
  StageRecord r;
  r.stage = "diffuse";
  r.keys = Json::parse(R"({"diffuse": {"drag": 0.5, "k_ta": 300}, "fluid": {"radius": 0.02}})");
  r.first_frame = first, r.last_frame = last;
  for (int f = first; f <= last; ++f) r.frame_inputs[f] = FileIdentity{1000u + uint64_t(f), 1700000000000000000 + f, 0};
  return r;
}

TEST(StageRecord, EqualRecordsAreCurrentAndALongerOneServesAShorterRange) {
  EXPECT_EQ(match_records(record(0, 9), record(0, 9)).kind, RecordMatch::Kind::Current);
  EXPECT_EQ(match_records(record(0, 9), record(0, 4)).kind, RecordMatch::Kind::Current);
}

TEST(StageRecord, AShorterCurrentRecordIsAPrefixToContinue) {
  const RecordMatch m = match_records(record(0, 4), record(0, 9));
  EXPECT_EQ(m.kind, RecordMatch::Kind::Prefix);
  EXPECT_NE(m.why.find("frame 4"), std::string::npos) << m.why;
}

TEST(StageRecord, AChangedKeyIsNamedWithBothValues) {
  StageRecord now = record(0, 9);
  now.keys["diffuse"]["drag"] = 0.9;
  const RecordMatch m = match_records(record(0, 9), now);
  EXPECT_EQ(m.kind, RecordMatch::Kind::Stale);
  EXPECT_EQ(m.why, "key diffuse.drag: 0.5 -> 0.9");
  now = record(0, 9);
  now.keys["diffuse"]["seed"] = 3;
  EXPECT_EQ(match_records(record(0, 9), now).why, "key diffuse.seed: absent -> 3");
}

TEST(StageRecord, AChangedInputFileIsNamedByFrame) {
  StageRecord now = record(0, 9);
  now.frame_inputs[6].mtime_ns += 1;  // re-exported, same size
  const RecordMatch m = match_records(record(0, 9), now);
  EXPECT_EQ(m.kind, RecordMatch::Kind::Stale);
  EXPECT_NE(m.why.find("input file of frame 6 changed"), std::string::npos) << m.why;
  // A change after the made range does not spoil the prefix.
  StageRecord longer = record(0, 12);
  longer.frame_inputs[11].size = 5;
  EXPECT_EQ(match_records(record(0, 9), longer).kind, RecordMatch::Kind::Prefix);
}

TEST(StageRecord, AnotherFirstFrameOrOtherInputIsStale) {
  EXPECT_EQ(match_records(record(2, 9), record(0, 9)).kind, RecordMatch::Kind::Stale);
  StageRecord with_bodies = record(0, 9);
  with_bodies.other_inputs["bodies.csv"] = {10, 20, 0};
  EXPECT_EQ(match_records(record(0, 9), with_bodies).kind, RecordMatch::Kind::Stale);
  StageRecord moved = with_bodies;
  moved.other_inputs["bodies.csv"].size = 11;
  EXPECT_NE(match_records(with_bodies, moved).why.find("bodies.csv changed"), std::string::npos);
}

TEST(StageRecord, RoundTripsThroughItsFileAndRemovalMeansUnfinished) {
  const testing::TempDir temp;
  const std::filesystem::path& dir = temp.path;
  EXPECT_FALSE(read_stage_record(dir));
  StageRecord r = record(3, 7);
  r.other_inputs["bodies.csv"] = {1, 2, 0};
  write_stage_record(dir, r);
  const auto back = read_stage_record(dir);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->to_json(), r.to_json());
  EXPECT_EQ(match_records(*back, r).kind, RecordMatch::Kind::Current);
  remove_stage_record(dir);
  EXPECT_FALSE(read_stage_record(dir));
}

TEST(JsonDifference, NamesTheFirstDifferingPath) {
  EXPECT_EQ(json_difference(Json::parse(R"({"a": {"b": [1, 2]}})"), Json::parse(R"({"a": {"b": [1, 3]}})")),
            "a.b[1]: 2 -> 3");
  EXPECT_EQ(json_difference(Json::parse(R"({"a": 1})"), Json::parse(R"({"a": 1})")), "");
  EXPECT_EQ(json_difference(Json::parse(R"({"a": 1})"), Json::parse(R"({})")), "a: 1 -> absent");
}

}  // namespace
}  // namespace spume
