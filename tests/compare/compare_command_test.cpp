// `spume compare` end to end through the binary: exit codes, summary.csv / summary.json figures for
// identical sequences, hand-worked one-pixel changes at and past each threshold as options set
// them, missing frames, other sizes, unreadable files, usage errors, thread-count independence,
// and stale images of an earlier run removed.
#include <gtest/gtest.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/support/run_spume.h"
#include "tests/compare/compare_test_support.h"
#include "render/image/png_io.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::flat_image;
using testing::fresh_dir;
using testing::read_csv;
using testing::run_spume;
using testing::with_change;

CommandResult compare(const std::string& arguments) { return run_spume("compare --quiet " + arguments); }

// Shell-quoted; appended piecewise, since GCC 12 warns falsely (-Wrestrict) on "'" + s + "'".
std::string q(const fs::path& p) {
  std::string s(1, '\'');
  s += p.string();
  s += '\'';
  return s;
}

std::string frame_name(int f) {
  char name[32];
  std::snprintf(name, sizeof name, "%04d.png", f);
  return name;
}

// The summary.csv row of a frame, as column name -> cell.
std::map<std::string, std::string> csv_row(const fs::path& out, const std::string& frame) {
  const auto rows = read_csv(out / "summary.csv");
  std::map<std::string, std::string> row;
  for (size_t i = 1; i < rows.size(); ++i)
    if (rows[i][0] == frame)
      for (size_t c = 0; c < rows[0].size(); ++c) row[rows[0][c]] = rows[i][c];
  return row;
}

TEST(CompareCommand, IdenticalSequencesPassWithZeroErrorAndInfinitePsnr) {
  const fs::path dir = fresh_dir("cmd_identical");
  for (int f = 0; f < 3; ++f) {
    const ImageRGB8 img = testing::random_image(32, 24, uint32_t(f));
    write_png(dir / "ref" / frame_name(f), img);
    write_png(dir / "new" / frame_name(f), img);
  }
  const CommandResult r = compare(q(dir / "ref" / "%04d.png") + " " + q(dir / "new") + " --out " + q(dir / "out"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("PASS, 3 frames: 0 fail, 3 pass (3 identical)"), std::string::npos) << r.output;
  const auto rows = read_csv(dir / "out" / "summary.csv");
  ASSERT_EQ(rows.size(), 5u);  // header, 3 frames, overall
  for (const auto& row : rows) EXPECT_EQ(row.size(), 23u);
  for (int f = 0; f < 3; ++f) {
    auto row = csv_row(dir / "out", frame_name(f));
    EXPECT_EQ(row["status"], "identical");
    EXPECT_EQ(row["number"], std::to_string(f));
    EXPECT_EQ(row["over_fail"], "0");
    EXPECT_EQ(row["over_fail_percent"], "0.000000");
    EXPECT_EQ(row["max_diff"], "0");
    EXPECT_EQ(row["mean_diff"], "0.000000");
    EXPECT_EQ(row["rmse"], "0.000000");
    EXPECT_EQ(row["psnr_db"], "inf");
    EXPECT_EQ(row["ssim"], "1.000000");
    EXPECT_EQ(row["diff_image"], "");  // only failing frames get difference images
  }
  EXPECT_EQ(rows.back()[0], "overall");
  EXPECT_EQ(rows.back()[3], "pass");
  const auto j = nlohmann::json::parse(testing::read_file(dir / "out" / "summary.json"));
  EXPECT_EQ(j["overall"]["verdict"], "pass");
  EXPECT_EQ(j["overall"]["identical"], 3);
  EXPECT_TRUE(j["overall"]["min_psnr_db"].is_null());  // infinite
  EXPECT_EQ(j["overall"]["min_ssim"], 1.0);
  EXPECT_EQ(j["frames"][1]["max_diff"], 0);
  EXPECT_TRUE(j["frames"][1]["psnr_db"].is_null());
  EXPECT_EQ(j["frames"][1]["ssim"], 1.0);
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "report.html"));
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "thumbs" / "0001_reference.png"));
  EXPECT_FALSE(fs::exists(dir / "out" / "diff"));
}

// One 100x100 grey pair per case, compared as two files: the exit status says pass (0) or fail (1).
int compare_change(const std::vector<std::array<int, 4>>& changes, const std::string& options,
                   std::string* output = nullptr) {
  static int n = 0;
  const fs::path dir = fresh_dir("cmd_threshold_" + std::to_string(n++));
  const ImageRGB8 grey = flat_image(100, 100, 100);
  ImageRGB8 edited = grey;
  for (const auto& [x, y, c, by] : changes) edited = with_change(edited, x, y, c, by);
  write_png(dir / "a.png", grey);
  write_png(dir / "b.png", edited);
  const CommandResult r = compare(q(dir / "a.png") + " " + q(dir / "b.png") + " " + options);
  if (output) *output = r.output;
  return r.status;
}

TEST(CompareCommand, ThresholdsJustAtAndJustPast) {
  // --fail (1 by default): with --failpercent 0 a single pixel over it fails the frame.
  EXPECT_EQ(compare_change({{5, 5, 1, 1}}, "--failpercent 0"), 0);
  EXPECT_EQ(compare_change({{5, 5, 1, 2}}, "--failpercent 0"), 1);
  EXPECT_EQ(compare_change({{5, 5, 1, 5}}, "--fail 5 --failpercent 0 --hardfail 255"), 0);
  EXPECT_EQ(compare_change({{5, 5, 1, 6}}, "--fail 5/255 --failpercent 0 --hardfail 255"), 1);
  // --failpercent (0.02 by default): 2 of 10000 pixels over 1/255 pass, 3 fail.
  EXPECT_EQ(compare_change({{1, 1, 0, 2}, {2, 2, 0, 2}}, ""), 0);
  EXPECT_EQ(compare_change({{1, 1, 0, 2}, {2, 2, 0, 2}, {3, 3, 0, 2}}, ""), 1);
  EXPECT_EQ(compare_change({{1, 1, 0, 2}, {2, 2, 0, 2}, {3, 3, 0, 2}}, "--failpercent 0.03"), 0);
  EXPECT_EQ(compare_change({{1, 1, 0, 2}, {2, 2, 0, 2}, {3, 3, 0, 2}, {4, 4, 0, 2}}, "--failpercent 0.03%"), 1);
  // --hardfail (3 by default): one pixel at 3 passes (0.01% over 1/255 is allowed), at 4 fails.
  EXPECT_EQ(compare_change({{9, 9, 2, 3}}, ""), 0);
  std::string out;
  EXPECT_EQ(compare_change({{9, 9, 2, 4}}, "", &out), 1);
  EXPECT_NE(out.find("largest difference 4/255 is over the hard limit 3/255 (1 pixel)"), std::string::npos) << out;
  EXPECT_EQ(compare_change({{9, 9, 2, 10}}, "--hardfail 10"), 0);
  EXPECT_EQ(compare_change({{9, 9, 2, 11}}, "--hardfail 10"), 1);
}

TEST(CompareCommand, MissingOtherSizeAndUnreadableFramesFailByName) {
  const fs::path dir = fresh_dir("cmd_problems");
  for (int f = 0; f < 5; ++f) write_png(dir / "ref" / frame_name(f), flat_image(32, 24, 50));
  write_png(dir / "new" / frame_name(0), flat_image(32, 24, 50));
  // 0001 missing in new
  write_png(dir / "new" / frame_name(2), flat_image(16, 12, 50));
  testing::write_file(dir / "new" / frame_name(3), "not a png at all");
  write_png(dir / "new" / frame_name(4), flat_image(32, 24, 50));
  write_png(dir / "new" / frame_name(5), flat_image(32, 24, 50));  // missing in reference
  const CommandResult r = compare(q(dir / "ref") + " " + q(dir / "new") + " --out " + q(dir / "out"));
  ASSERT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("FAIL, 6 frames: 4 fail, 2 pass"), std::string::npos) << r.output;
  auto row = csv_row(dir / "out", "0001.png");
  EXPECT_EQ(row["status"], "missing");
  EXPECT_EQ(row["reason"], "missing in new: no " + (dir / "new" / "0001.png").string());
  row = csv_row(dir / "out", "0005.png");
  EXPECT_EQ(row["status"], "missing");
  EXPECT_EQ(row["reason"], "missing in reference: no " + (dir / "ref" / "0005.png").string());
  row = csv_row(dir / "out", "0002.png");
  EXPECT_EQ(row["status"], "size-mismatch");
  EXPECT_NE(row["reason"].find("reference 32x24"), std::string::npos) << row["reason"];
  EXPECT_NE(row["reason"].find("new 16x12"), std::string::npos) << row["reason"];
  EXPECT_EQ(row["pixels"], "");
  row = csv_row(dir / "out", "0003.png");
  EXPECT_EQ(row["status"], "unreadable");
  EXPECT_NE(row["reason"].find("unreadable new: " + (dir / "new" / "0003.png").string() + ": not a PNG"),
            std::string::npos)
      << row["reason"];
  EXPECT_EQ(csv_row(dir / "out", "0004.png")["status"], "identical");
  // Worst first: the frames that could not be compared lead, unreadable first.
  EXPECT_EQ(csv_row(dir / "out", "0003.png")["rank"], "1");
  const auto j = nlohmann::json::parse(testing::read_file(dir / "out" / "summary.json"));
  EXPECT_EQ(j["overall"]["missing"], 2);
  EXPECT_EQ(j["overall"]["size_mismatch"], 1);
  EXPECT_EQ(j["overall"]["unreadable"], 1);
  EXPECT_EQ(j["overall"]["verdict"], "fail");
}

TEST(CompareCommand, UsageErrorsExitTwoAndSayWhatIsAllowed) {
  const fs::path dir = fresh_dir("cmd_usage");
  write_png(dir / "a.png", flat_image(4, 4, 0));
  const std::string a = q(dir / "a.png");
  EXPECT_EQ(run_spume("compare").status, 2);
  struct Case {
    std::string args, says;
  };
  for (const Case& c : std::vector<Case>{
           {a, "expected REFERENCE and NEW, got 1 argument"},
           {a + " " + q(dir / "missing.png"), "no such file or folder"},
           {a + " " + q(dir), "is a file but NEW"},
           {a + " " + a + " --fail 0.004", "(a fraction of full range, as idiff takes it? 0.004 x 255 = 1 level)"},
           {a + " " + a + " --fail 256", "--fail \"256\": expected a whole number of 8-bit levels from 0 to 255"},
           {a + " " + a + " --hardfail -1", "--hardfail \"-1\""},
           {a + " " + a + " --failpercent 101", "--failpercent \"101\": expected a percentage"},
           {a + " " + a + " --failpercent 1e-3", "--failpercent \"1e-3\""},
           {a + " " + a + " --frames 1", "--frames selects numbered frames"},
           {a + " " + a + " --scale 0", "--scale: \"0\" is not a whole number from 1 to 255"},
           {a + " " + a + " --fial 2", "spume compare: error: unknown option --fial (did you mean --fail?)"},
       }) {
    const CommandResult r = compare(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.says), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.find("spume compare: spume compare"), std::string::npos) << r.output;
  }
}

TEST(CompareCommand, SameOutputsForAnyThreadCount) {
  const fs::path dir = fresh_dir("cmd_threads");
  for (int f = 0; f < 7; ++f) {
    const ImageRGB8 img = testing::random_image(96, 54, uint32_t(100 + f));
    write_png(dir / "ref" / frame_name(f), img);
    ImageRGB8 changed = img;
    for (int k = 0; k < f * 40; ++k) changed.rgb[size_t(k * 37) % changed.rgb.size()] ^= uint8_t(1 + k % 7);
    write_png(dir / "new" / frame_name(f), changed);
  }
  std::string outputs[2];
  for (int threads : {1, 2}) {
    const fs::path out = dir / ("out" + std::to_string(threads));
    const CommandResult r = compare(q(dir / "ref") + " " + q(dir / "new") + " --threads " + std::to_string(threads) +
                                    " --out " + q(out));
    ASSERT_EQ(r.status, 1) << r.output;
    outputs[threads - 1] = r.output.substr(0, r.output.find("Saved: "));  // the folder names differ
  }
  EXPECT_EQ(outputs[0], outputs[1]);
  size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "out1")) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), dir / "out1");
    EXPECT_EQ(testing::read_file(entry.path()), testing::read_file(dir / "out2" / rel)) << rel;
    ++files;
  }
  EXPECT_EQ(files, 3u + 7 * 2 + 6 * 3);  // summaries and report, 2 thumbnails a frame, 3 images a failing frame
}

TEST(CompareCommand, ImagesOfAnEarlierRunAreRemoved) {
  const fs::path dir = fresh_dir("cmd_stale");
  write_png(dir / "ref" / "0000.png", flat_image(20, 20, 10));
  write_png(dir / "new" / "0000.png", flat_image(20, 20, 90));
  const std::string args = q(dir / "ref") + " " + q(dir / "new") + " --out " + q(dir / "out");
  ASSERT_EQ(compare(args).status, 1);
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "diff" / "0000_heat.png"));
  write_png(dir / "new" / "0000.png", flat_image(20, 20, 10));
  testing::write_file(dir / "out" / "mine.txt", "the user's");
  ASSERT_EQ(compare(args).status, 0);
  EXPECT_FALSE(fs::exists(dir / "out" / "diff" / "0000_heat.png"));
  EXPECT_FALSE(fs::exists(dir / "out" / "thumbs" / "0000_heat.png"));
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "thumbs" / "0000_new.png"));
  EXPECT_TRUE(fs::is_regular_file(dir / "out" / "mine.txt"));
}

// A report folder that cannot be made is no verdict: exit 2 with the folder and the system's reason,
// never 1 ("frames differ"), whether the frames agree or not, and before any frame is compared.
TEST(CompareCommand, AnUnwritableReportFolderExitsTwoNamingIt) {
  const fs::path dir = fresh_dir("cmd_unwritable_out");
  write_png(dir / "a.png", flat_image(4, 4, 0));
  write_png(dir / "b.png", flat_image(4, 4, 200));
  std::ofstream(dir / "plain_file") << "a file, so nothing can be created under it, not even by root\n";
  const fs::path out = dir / "plain_file" / "report";
  for (const char* other : {"a.png", "b.png"}) {
    const CommandResult r = compare(q(dir / "a.png") + " " + q(dir / other) + " --out " + q(out));
    EXPECT_EQ(r.status, 2) << other << "\n" << r.output;
    EXPECT_NE(r.output.find("--out " + out.string() + ": cannot create the report folder (Not a directory)"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("compare: FAIL"), std::string::npos) << r.output;
  }
}

}  // namespace
}  // namespace spume
