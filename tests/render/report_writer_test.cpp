// The report's writers: CSV quoting, markdown escaping, numbers, and the gnuplot script.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "sim/core/error.h"
#include "render/app/report/gnuplot_figure.h"
#include "render/app/report/report_table.h"
#include "tests/support/temp_dir.h"

namespace spume::report {
namespace {

TEST(ReportWriter, CsvQuotesOnlyCellsThatNeedItAndDoublesQuotes) {
  EXPECT_EQ(csv_cell("plain"), "plain");
  EXPECT_EQ(csv_cell("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_cell("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_cell("two\nlines"), "\"two\nlines\"");
  Table t;
  t.columns = {"name", "value"};
  t.add_row({"x,y", "1"});
  EXPECT_EQ(to_csv(t), "name,value\n\"x,y\",1\n");
}

TEST(ReportWriter, MarkdownKeepsPipesBackslashesAndNewlinesInsideTheCell) {
  EXPECT_EQ(markdown_cell("a|b"), "a\\|b");
  EXPECT_EQ(markdown_cell("c:\\dir"), "c:\\\\dir");
  EXPECT_EQ(markdown_cell("one\r\ntwo"), "one<br>two");
  Table t;
  t.columns = {"case", "result"};
  t.add_row({"A|B", "pass"});
  EXPECT_EQ(to_markdown(t), "| case | result |\n|---|---|\n| A\\|B | pass |\n");
}

TEST(ReportWriter, RowsMustMatchTheColumns) {
  Table t;
  t.columns = {"a", "b"};
  EXPECT_THROW(t.add_row({"1"}), Error);
}

TEST(ReportWriter, NumbersAreShortAndNeverEmpty) {
  EXPECT_EQ(num(0.000123456), "0.0001235");
  EXPECT_EQ(num(1234567.0), "1.235e+06");
  EXPECT_EQ(num(NAN), "nan");
  EXPECT_EQ(num(-INFINITY), "-inf");
}

TEST(ReportWriter, GnuplotScriptQuotesTitlesAndDropsPointsALogAxisCannotShow) {
  Figure f;
  Panel p{"a \"quoted\" title", "x (m)", "y (s)", true, true, false, {Series{"s", {{1, 2}, {0, 3}, {2, -1}, {4, 8}}, true}}};
  f.panels = {p};
  const std::string script = gnuplot_script(f, "/tmp/x.png");
  EXPECT_NE(script.find("set title \"a \\\"quoted\\\" title\""), std::string::npos) << script;
  EXPECT_NE(script.find("1 2\n4 8\nEOD"), std::string::npos) << script;  // (0,3) and (2,-1) left out
  EXPECT_NE(script.find("set logscale x 10"), std::string::npos);
  EXPECT_THROW(gnuplot_script(Figure{}, "/tmp/x.png"), Error);
}

TEST(ReportWriter, DrawsAPngWithGnuplot) {
  const testing::TempDir temp;
  const std::filesystem::path& dir = temp.path;
  Figure f;
  f.panels = {Panel{"t", "x", "y", false, false, false, {Series{"s", {{0, 0}, {1, 1}}, true}}}};
  draw_figure(f, dir / "plot.png", dir / "plot.gp");
  std::ifstream png(dir / "plot.png", std::ios::binary);
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "plot.gp"));
  // Nothing temporary is left behind.
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 2);
}

}  // namespace
}  // namespace spume::report
