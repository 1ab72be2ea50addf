// The conventions of the spume command line, through the binary: -h/--help on every command (options
// on stdout, exit 0), --version, usage errors exit 2 and name the command once, scene and input
// errors exit 1, option tables in aligned columns.
#include <gtest/gtest.h>
#include <unistd.h>

#include <embree3/rtcore_config.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <tuple>

#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

struct Output {
  int status = -1;
  std::string out, err;
};

// Runs spume with stdout and stderr kept apart.
Output spume(const std::string& arguments) {
  const testing::CommandResult r = testing::run_spume(arguments, testing::SpumeOptions::stderr_apart());
  return {r.status, r.output, r.err};
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

size_t count(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

struct CommandOptions {
  std::string command;
  std::vector<std::string> options;  // every option the README documents for it
};

const std::vector<std::string> kSceneOptions = {"--out",   "--threads", "--set", "--quiet",
                                                "--fluid", "--radius",  "--fps"};

std::vector<CommandOptions> documented_commands() {
  auto scene = [](std::vector<std::string> own) {
    own.insert(own.end(), kSceneOptions.begin(), kSceneOptions.end());
    return own;
  };
  return {
      {"run", scene({"--frames", "--overwrite", "--movie", "--force"})},
      {"simulate", scene({"--frames", "--bgeo", "--vdb", "--force"})},
      {"render", scene({"--frames", "--overwrite", "--movie"})},
      {"lookdev", scene({"--vary", "--frame", "--columns", "--tile-width", "--output"})},
      {"farm chunks", scene({"--chunk", "--frames"})},
      {"farm slurm", scene({"--chunk", "--frames", "--partition", "--max-running", "--sbatch", "--submit"})},
      {"info", {}},
      {"report", {"--quick", "--only", "--out", "--threads", "--quiet"}},
  };
}

TEST(CliConventions, HelpOnEveryCommandPrintsItsOptionsAndExitsZero) {
  for (const auto& [command, options] : documented_commands()) {
    for (const std::string help : {"--help", "-h", "scene.json --help"}) {
      const Output r = spume(command + " " + help);
      EXPECT_EQ(r.status, 0) << command << " " << help << "\n" << r.err;
      EXPECT_EQ(r.err, "") << command << " " << help;
      EXPECT_EQ(r.out.rfind("usage: spume " + command + " ", 0), 0u) << r.out;
      EXPECT_NE(r.out.find("\n  -h, --help "), std::string::npos) << r.out;
      for (const auto& option : options)
        EXPECT_NE(r.out.find("\n  " + option + " "), std::string::npos) << command << ": " << option << "\n" << r.out;
    }
  }
  const Output farm = spume("farm --help");
  EXPECT_EQ(farm.status, 0) << farm.err;
  EXPECT_NE(farm.out.find("  farm chunks "), std::string::npos) << farm.out;
  EXPECT_NE(farm.out.find("  farm slurm "), std::string::npos) << farm.out;
  const Output top = spume("--help");
  EXPECT_EQ(top.status, 0);
  for (const auto& c : documented_commands())
    EXPECT_NE(top.out.find("\n  " + c.command + " "), std::string::npos) << c.command;
}

TEST(CliConventions, CommandAlonePrintsItsOptionsToStderrAndExitsTwo) {
  for (const std::string command : {"run", "simulate", "render", "lookdev", "farm chunks", "farm slurm", "info"}) {
    const Output r = spume(command);
    EXPECT_EQ(r.status, 2) << command;
    EXPECT_EQ(r.out, "") << command;
    EXPECT_EQ(r.err.rfind("usage: spume " + command + " ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("\noptions:\n"), std::string::npos) << r.err;
  }
  const Output farm = spume("farm");
  EXPECT_EQ(farm.status, 2);
  EXPECT_NE(farm.err.find("farm slurm"), std::string::npos) << farm.err;
  EXPECT_EQ(spume("").status, 2);
}

// In every help, the descriptions of the option table start in one column, two spaces past the
// longest option, and wrapped lines continue in that column.
TEST(CliConventions, OptionTablesAreAligned) {
  const std::regex row("  (-\\S.*?\\S)  +(\\S.*)");
  for (const auto& c : documented_commands()) {
    const std::string help = spume(c.command + " --help").out;
    std::istringstream lines(help.substr(help.find("\noptions:\n") + 10));
    std::vector<size_t> starts;
    size_t longest = 0;
    std::vector<std::string> continuations;
    for (std::string line; std::getline(lines, line) && !line.empty();) {
      std::smatch m;
      if (std::regex_match(line, m, row)) {
        starts.push_back(size_t(m.position(2)));
        longest = std::max(longest, size_t(m.length(1)));
      } else {
        continuations.push_back(line);
      }
    }
    ASSERT_GE(starts.size(), c.options.size() + 1) << help;
    for (size_t s : starts) EXPECT_EQ(s, 2 + longest + 2) << c.command << "\n" << help;
    for (const auto& line : continuations) {
      EXPECT_EQ(line.find_first_not_of(' '), 2 + longest + 2) << c.command << ": " << line;
    }
  }
}

// The version as CMakeLists.txt declares it: project(spume VERSION x.y ...).
std::string declared_version() {
  std::ifstream in(fs::path(SPUME_SOURCE_DIR) / "CMakeLists.txt");
  std::stringstream text;
  text << in.rdbuf();
  std::smatch m;
  const std::string s = text.str();
  return std::regex_search(s, m, std::regex("project\\(spume VERSION ([0-9.]+)")) ? m[1].str() : "?";
}

TEST(CliConventions, VersionNamesTheBuildAndItsLibraries) {
  for (const char* flag : {"--version", "-V"}) {
    const Output r = spume(flag);
    EXPECT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(first_line(r.out), "spume " + declared_version()) << r.out;
    EXPECT_NE(r.out.find(std::string("Embree:  ") + RTC_VERSION_STRING + "\n"), std::string::npos) << r.out;
#if defined(__GNUC__) && !defined(__clang__)
    // The tests are built by the same compiler as spume.
    EXPECT_NE(r.out.find(std::string("GCC ") + __VERSION__), std::string::npos) << r.out;
#endif
    EXPECT_NE(r.out.find(std::string("build:   ") + SPUME_BUILD_TYPE + ", "), std::string::npos) << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("\nMesa: .*Mesa [0-9]+\\.[0-9]+"))) << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("\nEigen:   [0-9]+\\.[0-9]+\\.[0-9]+\n"))) << r.out;
    EXPECT_TRUE(std::regex_search(r.out, std::regex("\noneTBB:  [0-9]+\\.[0-9]+"))) << r.out;
  }
}

struct UsageCase {
  std::string arguments;
  std::string command;  // as the message must name it, once
  std::string message;  // after "spume COMMAND: error: "
};

TEST(CliConventions, UsageErrorsExitTwoNamingTheCommandOnce) {
  const UsageCase cases[] = {
      {"run --thread 2 x.json", "run", "unknown option --thread (did you mean --threads?)"},
      {"farm slurm x.json --chunk 2 --partitio p", "farm slurm",
       "unknown option --partitio (did you mean --partition?)"},
      {"report --quik", "report", "unknown option --quik (did you mean --quick?)"},
      {"render x.json --frames", "render", "--frames needs a value: --frames SPEC"},
      {"run x.json --out a --out b", "run", "--out given twice (\"a\" and \"b\"); give it once"},
      {"run x.json --quiet=1", "run", "--quiet takes no value (found --quiet=1)"},
      {"run a.json b.json", "run", "expected SCENE.json [options]; found 2 operands (b.json is one too many)"},
      {"report a.json b.json", "report", "expected [SCENE.json] [options]; found 2 operands (b.json is one too many)"},
      {"simulate x.json --threads x", "simulate", "--threads: \"x\" is not a whole number from 1 to 1024"},
      {"farm chunks x.json", "farm chunks", "--chunk N (frames per chunk) is required"},
      {"farm chunks x.json --chunk 0", "farm chunks", "--chunk: \"0\" is not a whole number from 1 to 1073741824"},
      {"run --fluid 'a_%d.bgeo'", "run", "--fluid needs --radius R (the fluid particle radius in m)"},
      {"run x.json --radius 0.02", "run", "--radius, --fps and --tank go with --fluid"},
      {"run --fluid 'a_%d.bgeo' --radius 2cm", "run", "--radius: \"2cm\" is not a number"},
      {"report --only surface,foam", "report",
       "--only: \"foam\" is not a study; allowed: render,diffuse,fluid,surface,stability (comma-separated)"},
      {"lookdev x.json --vary spray.radius=1,2", "lookdev",
       "--vary \"spray.radius=1,2\": look-dev varies render.* keys only"},
      {"lookdev x.json --tile-width 8", "lookdev", "--tile-width: \"8\" is not a whole number from 16 to 4096"},
  };
  for (const auto& c : cases) {
    const Output r = spume(c.arguments);
    EXPECT_EQ(r.status, 2) << c.arguments << "\n" << r.err;
    const std::string line = first_line(r.err);
    EXPECT_EQ(line.rfind("spume " + c.command + ": error: " + c.message, 0), 0u) << c.arguments << "\n" << r.err;
    EXPECT_EQ(count(line, "spume " + c.command + ":"), 1u) << line;
    EXPECT_NE(r.err.find("'spume " + c.command + " --help'"), std::string::npos) << r.err;
  }
}

// The frame-spec syntax is checked before the scene is read: the missing scene is never reached.
TEST(CliConventions, FrameSpecSyntaxIsAUsageError) {
  for (const std::string arguments : {"render /nonexistent.json --frames 0-x", "run /nonexistent.json --frames 5-3",
                                      "simulate /nonexistent.json --frames 0-6:2",
                                      "farm chunks /nonexistent.json --chunk 2 --frames 1,,2"}) {
    const Output r = spume(arguments);
    EXPECT_EQ(r.status, 2) << arguments << "\n" << r.err;
    EXPECT_NE(first_line(r.err).find("error: --frames: "), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_EQ(r.err.find("nonexistent"), std::string::npos) << r.err;
  }
}

TEST(CliConventions, UnknownCommandsSuggestTheClosest) {
  Output r = spume("rn scene.json");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(first_line(r.err), "spume: error: unknown command \"rn\" (did you mean \"run\"?)");
  r = spume("farm slrum scene.json");
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(first_line(r.err), "spume farm: error: unknown subcommand \"slrum\" (did you mean \"slurm\"?)");
}

class SceneErrors : public ::testing::Test {
 protected:
  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

TEST_F(SceneErrors, ExitOneNamingTheCommandOnce) {
  std::ofstream(dir / "bad.json") << "{\"fluid\": {,}";
  // A solver scene: it reads without any input file, so the unknown key is what fails.
  std::ofstream(dir / "typo.json") << R"({"fluid": {"source": "solver", "radius": 0.025,
      "blocks": [{"min": [0.1, 0.1, 0.1], "max": [0.3, 0.3, 0.3]}]},
      "solids": [{"type": "tank", "min": [0, 0, 0], "max": [0.4, 0.6, 0.4]}], "diffuse": {"k_taa": 1}})";
  const std::tuple<std::string, std::string, std::string> cases[] = {
      {"run", dir / "missing.json", "missing.json: cannot open the scene file (no such file)"},
      {"simulate", dir / "bad.json", "bad.json:1: not valid JSON"},
      {"render", dir / "typo.json", "unknown key:\n  /diffuse/k_taa (did you mean \"k_ta\"?)"},
      {"info", dir / "missing.bgeo", "missing.bgeo: no such file"},
  };
  for (const auto& [command, file, expected] : cases) {
    const Output r = spume(command + " " + file);
    EXPECT_EQ(r.status, 1) << command << " " << file << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("spume " + command + ": error: " + file, 0), 0u) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(count(r.err, "spume " + command + ":"), 1u) << r.err;
    EXPECT_EQ(r.err.find("--help"), std::string::npos) << r.err;  // not a usage error
  }
}

// A --set that is not KEY=VALUE is the command line's fault, found only once the scene is read.
TEST_F(SceneErrors, MalformedSetIsAUsageError) {
  std::ofstream(dir / "s.json") << R"({"fluid": {"files": "f_%d.bgeo", "radius": 0.02}})";
  const Output r = spume("simulate " + (dir / "s.json").string() + " --set diffuse.k_ta");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("spume simulate: error: --set diffuse.k_ta: expected key.path=value"), std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace spume
