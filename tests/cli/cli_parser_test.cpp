// The command-line parser and the help tables (render/app/cli/cli_args.h, cli_help.h), without the binary.
#include <gtest/gtest.h>

#include <functional>

#include "render/app/cli/cli_args.h"
#include "render/app/cli/cli_help.h"
#include "tests/support/error_of.h"

namespace spume::cli {
namespace {

using testing::error_of;

const std::vector<OptionSpec> kSpecs = {
    {"out", "DIR", "output root"},
    {"threads", "N", "worker threads"},
    {"set", "KEY=VALUE", "override a key", true},
    {"quiet", "", "no progress"},
};

TEST(CliParser, ReadsOperandsFlagsValuesAndRepeats) {
  const ParsedArgs a =
      parse({"scene.json", "--out", "o", "--set", "a=1", "--quiet", "--set=b.c=2", "--threads=3"}, kSpecs);
  EXPECT_EQ(a.positional, std::vector<std::string>{"scene.json"});
  EXPECT_EQ(a.value("out"), "o");
  EXPECT_EQ(a.value("threads"), "3");
  EXPECT_EQ(a.all("set"), (std::vector<std::string>{"a=1", "b.c=2"}));
  EXPECT_TRUE(a.has("quiet"));
  EXPECT_FALSE(a.has("help"));
  EXPECT_FALSE(a.help);
}

TEST(CliParser, DoubleDashEndsOptionsAndDashAloneIsAnOperand) {
  const ParsedArgs a = parse({"--quiet", "--", "--out", "-", "-h"}, kSpecs);
  EXPECT_EQ(a.positional, (std::vector<std::string>{"--out", "-", "-h"}));
  EXPECT_FALSE(a.help);
  EXPECT_EQ(parse({"-"}, kSpecs).positional, std::vector<std::string>{"-"});
}

TEST(CliParser, HelpStopsParsingSoLaterMistakesDoNotHideIt) {
  for (const char* help : {"-h", "--help"}) {
    const ParsedArgs a = parse({"scene.json", help, "--no-such-option", "--out"}, kSpecs);
    EXPECT_TRUE(a.help) << help;
  }
  // A value that looks like --help is a value, not a help request.
  const ParsedArgs a = parse({"--set", "--help"}, kSpecs);
  EXPECT_FALSE(a.help);
  EXPECT_EQ(a.all("set"), std::vector<std::string>{"--help"});
}

TEST(CliParser, UnknownOptionsAreUsageErrorsWithTheClosestOption) {
  EXPECT_EQ(error_of<UsageError>([] { parse({"--thread", "2"}, kSpecs); }),
            "unknown option --thread (did you mean --threads?)");
  EXPECT_EQ(error_of<UsageError>([] { parse({"--qiet"}, kSpecs); }), "unknown option --qiet (did you mean --quiet?)");
  // Far from every option, but the start of only one.
  EXPECT_EQ(error_of<UsageError>([] { parse({"--thr", "2"}, kSpecs); }), "unknown option --thr (did you mean --threads?)");
  EXPECT_EQ(error_of<UsageError>([] { parse({"--frobnicate"}, kSpecs); }), "unknown option --frobnicate");
  EXPECT_NE(error_of<UsageError>([] { parse({"-q"}, kSpecs); }).find("unknown option -q"), std::string::npos);
}

TEST(CliParser, MissingRepeatedAndUnexpectedValuesAreUsageErrors) {
  EXPECT_EQ(error_of<UsageError>([] { parse({"scene.json", "--out"}, kSpecs); }), "--out needs a value: --out DIR");
  EXPECT_EQ(error_of<UsageError>([] { parse({"--out", "a", "--out=b"}, kSpecs); }),
            "--out given twice (\"a\" and \"b\"); give it once");
  EXPECT_EQ(error_of<UsageError>([] { parse({"--quiet=yes"}, kSpecs); }), "--quiet takes no value (found --quiet=yes)");
}

TEST(CliParser, BadOptionValuesAreUsageErrors) {
  EXPECT_EQ(error_of<UsageError>([] { parse_int("x", "--threads", 1, 1024); }),
            "--threads: \"x\" is not a whole number from 1 to 1024");
  EXPECT_EQ(error_of<UsageError>([] { parse_int("0", "--threads", 1, 1024); }),
            "--threads: \"0\" is not a whole number from 1 to 1024");
  EXPECT_EQ(error_of<UsageError>([] { parse_int("3.5", "--chunk", 1, 10); }),
            "--chunk: \"3.5\" is not a whole number from 1 to 10");
  EXPECT_EQ(parse_int("17", "--chunk", 1, 100), 17);
  EXPECT_EQ(error_of<UsageError>([] { parse_double("0.02m", "--radius"); }), "--radius: \"0.02m\" is not a number");
  EXPECT_DOUBLE_EQ(parse_double("2e-2", "--radius"), 0.02);
  EXPECT_NE(error_of<UsageError>([] { check_frame_spec("0-x", "--frames"); }).find("--frames"), std::string::npos);
  EXPECT_NE(error_of<UsageError>([] { check_frame_spec("5-3", "--frames"); }).find("5-3"), std::string::npos);
  check_frame_spec("1-3,5,10-20:2", "--frames");  // no throw
  EXPECT_EQ(parse_frame_range("4-9", "--frames"), std::make_pair(4, 9));
  EXPECT_NE(error_of<UsageError>([] { parse_frame_range("0-6:2", "--frames"); }).find("is not one unbroken range"),
            std::string::npos);
  EXPECT_NE(error_of<UsageError>([] { parse_frame_range("0-x", "--frames"); }).find("accepted forms"), std::string::npos);
}

TEST(CliParser, AsUsageTurnsErrorsIntoUsageErrorsAndKeepsTheMessage) {
  EXPECT_EQ(error_of<UsageError>([] { as_usage([] { fail("--set x: bad"); }); }), "--set x: bad");
  EXPECT_EQ(as_usage([] { return 7; }), 7);
}

// Columns worked out by hand: the longest left cell is "  -h, --help" and "  --set KEY=VALUE"
// (17 characters), so every description starts after 17 + 2 = 19 characters.
TEST(CliHelp, OptionTableAlignsDescriptionsInOneColumn) {
  EXPECT_EQ(option_table(kSpecs),
            "  -h, --help       print this help and exit\n"
            "  --out DIR        output root\n"
            "  --threads N      worker threads\n"
            "  --set KEY=VALUE  override a key (repeatable)\n"
            "  --quiet          no progress\n");
}

TEST(CliHelp, LongDescriptionsWrapInTheirColumn) {
  // Width 30: the right column starts at 2 + 3 + 2 = 7, which would leave 23 characters; descriptions
  // never wrap narrower than 30, so the first line breaks before "seven" (27 + 6 > 30).
  const std::string text = aligned_table({{"abc", "one two three four five six seven eight nine ten eleven"},
                                          {"x", "short"}},
                                         30);
  EXPECT_EQ(text,
            "  abc  one two three four five six\n"
            "       seven eight nine ten eleven\n"
            "  x    short\n");
}

TEST(CliHelp, HelpTextHasUsageLinesSummaryTableAndNotes) {
  CommandSpec spec;
  spec.name = "farm chunks";
  spec.forms = {"SCENE.json --chunk N [options]", "--fluid PATTERN --radius R --chunk N [options]"};
  spec.summary = "frame chunks";
  spec.options = {{"chunk", "N", "frames per chunk"}};
  spec.notes = {"example: here"};
  EXPECT_EQ(help_text(spec),
            "usage: spume farm chunks SCENE.json --chunk N [options]\n"
            "   or: spume farm chunks --fluid PATTERN --radius R --chunk N [options]\n"
            "frame chunks\n"
            "\n"
            "options:\n"
            "  -h, --help  print this help and exit\n"
            "  --chunk N   frames per chunk\n"
            "\n"
            "example: here\n");
}

}  // namespace
}  // namespace spume::cli
