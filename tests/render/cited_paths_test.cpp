// Cited paths exist: every repository file that a comment of the sources or a document names is there,
// and every link of the documents reaches a file and, with an anchor, one of its headings. A file that
// moves or is renamed then fails here, naming the citing file and line, instead of leaving readers a
// path to nowhere.
//
// What counts as a cited path is narrow, so that the check is exact: a token of path characters
// (letters, digits, _ - . /) that starts a word with a folder of the repository (sim/, render/, tests/,
// scenes/, .ci/) and ends in an extension the repository's files have. Outputs (out/..., OUT/<scene>/...),
// users' files and patterns (`scenes/<name>.json`, `tests/golden/*.json`) are not citations: they start
// elsewhere, or a character that no path has here (< * % #) ends the token before any extension.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace spume {
namespace {

namespace fs = std::filesystem;

struct Citation {
  int line;
  std::string path;
  bool operator==(const Citation&) const = default;
};

bool is_path_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' || c == '/';
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

bool is_repository_path(const std::string& token) {
  static const std::vector<std::string> folders = {"sim/", "render/", "tests/", "scenes/", ".ci/"};
  static const std::set<std::string> extensions = {"h",   "cpp", "md",  "json", "png", "csv", "txt",
                                                   "sh",  "py",  "gp",  "bgeo", "sc",  "gz",  "vtk",
                                                   "vtu", "vtp", "ply", "vdb",  "uni", "spf", "spd"};
  bool in_folder = false;
  for (const std::string& f : folders) in_folder = in_folder || (starts_with(token, f) && token.size() > f.size());
  if (!in_folder) return false;
  const std::string name = token.substr(token.rfind('/') + 1);
  const size_t dot = name.rfind('.');
  return dot != std::string::npos && dot > 0 && extensions.count(name.substr(dot + 1)) > 0;
}

// The repository paths cited in `text`, with their line numbers (from 1).
std::vector<Citation> cited_paths(const std::string& text) {
  std::vector<Citation> found;
  int line = 1;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n') ++line;
    if (!is_path_char(text[i]) || (i > 0 && is_path_char(text[i - 1]))) continue;
    size_t end = i;
    while (end < text.size() && is_path_char(text[end])) ++end;
    std::string token = text.substr(i, end - i);
    while (!token.empty() && token.back() == '.') token.pop_back();  // a sentence's full stop
    if (is_repository_path(token)) found.push_back({line, token});
    i = end - 1;
  }
  return found;
}

// The comments of a C++ source, everything else blanked (newlines kept, so lines keep their numbers):
// string and character literals, raw strings included, are code, and may name files that are meant
// not to exist.
std::string comments_of(const std::string& source) {
  std::string out(source.size(), ' ');
  for (size_t i = 0; i < source.size(); ++i)
    if (source[i] == '\n') out[i] = '\n';
  size_t i = 0;
  while (i < source.size()) {
    if (source.compare(i, 2, "//") == 0) {
      const size_t end = std::min(source.find('\n', i), source.size());
      out.replace(i, end - i, source, i, end - i);
      i = end;
    } else if (source.compare(i, 2, "/*") == 0) {
      const size_t end = std::min(source.find("*/", i + 2), source.size() - 2) + 2;
      for (size_t k = i; k < end; ++k) out[k] = source[k];
      i = end;
    } else if (source.compare(i, 2, "R\"") == 0 && (i == 0 || !is_path_char(source[i - 1]))) {
      const size_t open = source.find('(', i);
      const std::string close = ")" + source.substr(i + 2, open - i - 2) + "\"";
      i = std::min(source.find(close, open), source.size() - close.size()) + close.size();
    } else if (source[i] == '"' || source[i] == '\'') {
      const char quote = source[i];
      for (++i; i < source.size() && source[i] != quote && source[i] != '\n'; ++i)
        if (source[i] == '\\') ++i;
      ++i;
    } else {
      ++i;
    }
  }
  return out;
}

// A heading's anchor as GitHub makes it: lower case, punctuation dropped, spaces to hyphens.
std::string anchor_of(const std::string& heading) {
  std::string text = heading.substr(heading.find_first_not_of('#'));
  std::string anchor;
  for (char c : text.substr(text.find_first_not_of(' '))) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '-' || c == '_' || u >= 0x80) anchor += char(std::tolower(u));
    else if (c == ' ') anchor += '-';
  }
  return anchor;
}

std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The anchors of a markdown file's headings (lines in code fences are not headings).
std::set<std::string> anchors_in(const fs::path& markdown) {
  std::set<std::string> anchors;
  std::istringstream lines(read(markdown));
  bool fenced = false;
  for (std::string line; std::getline(lines, line);) {
    if (starts_with(line, "```")) fenced = !fenced;
    else if (!fenced && starts_with(line, "#")) anchors.insert(anchor_of(line));
  }
  return anchors;
}

// The documents (README.md and the .md files under the source folders, third-party data aside) and
// the C++ sources, relative to `root`.
std::vector<fs::path> files_under(const fs::path& root, const std::set<std::string>& extensions) {
  std::vector<fs::path> files;
  if (extensions.count(".md")) files.push_back("README.md");
  for (const char* side : {"sim", "render", "tests", "scenes"}) {
    for (const auto& e : fs::recursive_directory_iterator(root / side)) {
      const fs::path file = fs::relative(e.path(), root);
      if (e.is_regular_file() && extensions.count(file.extension().string()) &&
          !starts_with(file.generic_string(), "tests/data/"))
        files.push_back(file);
    }
  }
  return files;
}

TEST(CitedPaths, EveryRepositoryFileCitedInACommentOrADocumentExists) {
  const fs::path root = SPUME_SOURCE_DIR;
  size_t checked = 0;
  for (const fs::path& file : files_under(root, {".md", ".h", ".cpp"})) {
    const std::string text = read(root / file);
    for (const Citation& c : cited_paths(file.extension() == ".md" ? text : comments_of(text))) {
      ++checked;
      EXPECT_TRUE(fs::exists(root / c.path))
          << file.generic_string() << ":" << c.line << " cites " << c.path << ", which does not exist";
    }
  }
  EXPECT_GT(checked, 100u) << "the rule finds almost no citations: is it still reading the files?";
}

TEST(CitedPaths, EveryLinkOfADocumentReachesAFileAndItsHeading) {
  const fs::path root = SPUME_SOURCE_DIR;
  const std::regex link(R"(\]\(([^)\s]+)\))");
  for (const fs::path& document : files_under(root, {".md"})) {
    const std::string text = read(root / document);
    int line = 1;
    size_t counted_to = 0;
    for (auto m = std::sregex_iterator(text.begin(), text.end(), link); m != std::sregex_iterator(); ++m) {
      line += int(std::count(text.begin() + long(counted_to), text.begin() + m->position(), '\n'));
      counted_to = size_t(m->position());
      const std::string target = (*m)[1];
      if (starts_with(target, "http://") || starts_with(target, "https://") || starts_with(target, "mailto:")) continue;
      const size_t hash = target.find('#');
      const std::string path = target.substr(0, hash);
      const fs::path file = path.empty() ? root / document : (root / document).parent_path() / path;
      const std::string where = document.generic_string() + ":" + std::to_string(line) + " links to " + target;
      if (!fs::exists(file)) {
        ADD_FAILURE() << where << ", which does not exist";
      } else if (hash != std::string::npos && file.extension() == ".md") {
        EXPECT_EQ(anchors_in(file).count(target.substr(hash + 1)), 1u) << where << ": no such heading";
      }
    }
  }
}

TEST(CitedPaths, TheRuleTakesRepositoryPathsAndNothingElse) {
  const std::string text =
      "see sim/MODEL.md.\n"                                  // a full stop is no part of the path
      "`tests/render/layout_test.cpp:12` and (render/gl/environment.h)\n"
      "OUT/<scene>/frames/0000.png out/tests/golden/x_compare/report.html\n"  // outputs
      "scenes/<name>.json tests/golden/*.json sim/io/ render/app/report\n"    // patterns, folders
      "build/tests/spume_e2e_tests build/bench/bench_fluid.cpp .ci/run .ci/setup.sh\n";
  const std::vector<Citation> expected = {{1, "sim/MODEL.md"},
                                          {2, "tests/render/layout_test.cpp"},
                                          {2, "render/gl/environment.h"},
                                          {5, ".ci/setup.sh"}};
  EXPECT_EQ(cited_paths(text), expected);
}

TEST(CitedPaths, OnlyTheCommentsOfASourceAreRead) {
  const std::string source =
      "// cites sim/core/error.h\n"
      "const char* a = \"tests/sim/missing_test.cpp\";  // and render/gl/gl_api.h\n"
      "const char* b = R\"x(sim/nowhere.h \" // tests/nowhere.cpp)x\";\n"
      "char c = '\"'; /* sim/fluid/solver.h\n"
      "   tests/render/key_tables_test.cpp */ int d = 0;\n";
  const std::vector<Citation> expected = {{1, "sim/core/error.h"},
                                          {2, "render/gl/gl_api.h"},
                                          {4, "sim/fluid/solver.h"},
                                          {5, "tests/render/key_tables_test.cpp"}};
  EXPECT_EQ(cited_paths(comments_of(source)), expected);
}

TEST(CitedPaths, AnchorsAreTheHeadingsAsGitHubWritesThem) {
  EXPECT_EQ(anchor_of("## 10. The fluid solver's walls and deep water"), "10-the-fluid-solvers-walls-and-deep-water");
  EXPECT_EQ(anchor_of("### Blender (Mantaflow)"), "blender-mantaflow");
  EXPECT_EQ(anchor_of("## 4. Diffuse simulator (`bench_diffuse`)"), "4-diffuse-simulator-bench_diffuse");
  EXPECT_EQ(anchor_of("## Quick start (Debian 12, as root)"), "quick-start-debian-12-as-root");
}

}  // namespace
}  // namespace spume
