// What a command says on stderr (core/messages.h): quiet hides notes and progress, never warnings;
// each warning is said once and kept; a stage record carries its warnings without their changing
// whether outputs are current.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include "sim/core/messages.h"
#include "sim/core/progress.h"
#include "sim/io/stage_record.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

// stderr of the code run by `body`, through a file (fd 2 redirected for the duration).
template <class Body>
std::string captured_stderr(Body body) {
  const testing::TempDir temp;
  const std::string path = (temp.path / "stderr.txt").string();
  std::fflush(stderr);
  const int saved = ::dup(2);
  FILE* file = std::fopen(path.c_str(), "w");
  ::dup2(::fileno(file), 2);
  body();
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  std::fclose(file);
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

class Messages : public ::testing::Test {
 protected:
  void SetUp() override { messages::reset(); }
  void TearDown() override { messages::reset(); }
};

TEST_F(Messages, QuietHidesNotesAndProgressButNotWarnings) {
  messages::set_quiet(true);
  const std::string err = captured_stderr([] {
    messages::note("domain: [0, 0, 0] - [1, 1, 1]");
    Progress progress("simulate x", 3, false);
    progress.update(1, "1 spray");
    progress.note("diffuse: simulating");
    messages::warning("frame 3 removed 40 diffuse particles");
    progress.finish();
  });
  EXPECT_EQ(err, "warning: frame 3 removed 40 diffuse particles\n");
}

TEST_F(Messages, LoudPrintsAllInOrder) {
  const std::string err = captured_stderr([] {
    messages::note("a note");
    messages::warning("warning: given with its prefix");
    messages::report("another note");
    messages::report("warning: a warning in a mixed list");
  });
  EXPECT_EQ(err, "a note\nwarning: given with its prefix\nanother note\nwarning: a warning in a mixed list\n");
}

TEST_F(Messages, EachWarningIsSaidOnceAndKeptInOrder) {
  messages::set_quiet(true);
  const std::string err = captured_stderr([] {
    messages::warning("b");
    messages::warning("a");
    messages::warning("warning: b");  // the same text as the first, prefixed
    messages::warning("c");
  });
  EXPECT_EQ(err, "warning: b\nwarning: a\nwarning: c\n");
  EXPECT_EQ(messages::warnings(), (std::vector<std::string>{"warning: b", "warning: a", "warning: c"}));
  EXPECT_EQ(messages::warnings_since(2), (std::vector<std::string>{"warning: c"}));
  EXPECT_TRUE(messages::warnings_since(3).empty());
}

TEST_F(Messages, ARecordKeepsItsWarningsAndTheyDoNotMakeItStale) {
  const testing::TempDir temp;
  StageRecord made;
  made.stage = "diffuse";
  made.first_frame = 1, made.last_frame = 4;
  made.warnings = {"warning: x", "warning: y"};
  write_stage_record(temp.path, made);
  const std::optional<StageRecord> read = read_stage_record(temp.path);
  ASSERT_TRUE(read);
  EXPECT_EQ(read->warnings, made.warnings);
  StageRecord wanted = made;
  wanted.warnings.clear();
  EXPECT_EQ(match_records(*read, wanted).kind, RecordMatch::Kind::Current);
  // Said again when reused, each once, quiet or not.
  messages::set_quiet(true);
  const std::string err = captured_stderr([&] {
    messages::warning("warning: y");
    repeat_warnings(read);
  });
  EXPECT_EQ(err, "warning: y\nwarning: x\n");
}

TEST_F(Messages, MergedWarningsKeepTheEarlierOnesFirstWithoutRepeats) {
  EXPECT_EQ(merged_warnings({"warning: a", "warning: b"}, {"warning: b", "warning: c"}),
            (std::vector<std::string>{"warning: a", "warning: b", "warning: c"}));
}

}  // namespace
}  // namespace spume
