// The parts include each other in one direction only (README, Layout), read from the sources: every
// quoted include is resolved to the file it names, and the parts' include graph is checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace spume {
namespace {

namespace fs = std::filesystem;

// The part a file belongs to: "sim/fluid", "render/gl", and inside render/app, the command layer
// ("render/app", the files directly in it) apart from "render/app/compare", "render/app/report", ...
std::string part_of(const fs::path& relative) {
  std::vector<std::string> parts;
  for (const fs::path& p : relative) parts.push_back(p.string());
  if (parts.size() < 2) return parts.front();
  if (parts[0] == "render" && parts[1] == "app")
    return parts.size() > 3 ? "render/app/" + parts[2] : "render/app";
  if (parts[0] == "tests") return "tests";
  return parts[0] + "/" + parts[1];
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

struct Layout {
  std::map<std::string, std::set<std::string>> edges;  // part -> the parts it includes
  std::vector<std::string> violations;
};

// Reads every .h and .cpp under sim/, render/ and tests/ of `root`. An include must name a file by
// its path from the repository root (the one include root): a path relative to the including
// file, or one that a file beside it would shadow, is a violation, since two folders could answer.
Layout read_layout(const fs::path& root) {
  Layout layout;
  const std::regex include(R"(^\s*#\s*include\s+"([^"]+)\")");
  for (const char* side : {"sim", "render", "tests"}) {
    if (!fs::is_directory(root / side)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root / side)) {
      const std::string ext = e.path().extension().string();
      if (ext != ".h" && ext != ".cpp") continue;
      const fs::path file = fs::relative(e.path(), root);
      const std::string from = part_of(file);
      std::ifstream in(e.path());
      int line_number = 0;
      for (std::string line; std::getline(in, line);) {
        ++line_number;
        std::smatch m;
        if (!std::regex_search(line, m, include)) continue;
        const std::string name = m[1];
        const std::string where = file.string() + ":" + std::to_string(line_number) + " includes \"" + name + "\"";
        if (!fs::is_regular_file(root / name)) {
          layout.violations.push_back(where + ": not a file named from the repository root");
          continue;
        }
        if (fs::exists(e.path().parent_path() / name)) {
          layout.violations.push_back(where + ": a file beside it answers to the same path");
          continue;
        }
        const std::string to = part_of(fs::path(name));
        if (to != from) layout.edges[from].insert(to);
      }
    }
  }
  return layout;
}

// One cycle through the parts' includes, as "a -> b -> a", or "" when they form none.
std::string find_cycle(const std::map<std::string, std::set<std::string>>& edges) {
  std::map<std::string, int> state;  // 1 on the current path, 2 finished
  std::vector<std::string> path;
  std::string cycle;
  std::function<bool(const std::string&)> visit = [&](const std::string& part) {
    state[part] = 1;
    path.push_back(part);
    if (auto it = edges.find(part); it != edges.end())
      for (const std::string& next : it->second) {
        if (state[next] == 1) {
          for (auto p = std::find(path.begin(), path.end(), next); p != path.end(); ++p) cycle += *p + " -> ";
          cycle += next;
          return true;
        }
        if (state[next] == 0 && visit(next)) return true;
      }
    path.pop_back();
    state[part] = 2;
    return false;
  };
  for (const auto& [part, _] : edges)
    if (state[part] == 0 && visit(part)) return cycle;
  return "";
}

// Everything wrong with the layout under `root`, one line each.
std::vector<std::string> layout_violations(const fs::path& root) {
  Layout layout = read_layout(root);
  std::vector<std::string>& v = layout.violations;
  if (const std::string cycle = find_cycle(layout.edges); !cycle.empty()) v.push_back("the parts include in a cycle: " + cycle);
  // spume_frames: the one library of sim/ the renderer links (frame types, caches, solids, keys).
  const std::set<std::string> frames_library = {"sim/core", "sim/io", "sim/geometry", "sim/keys"};
  for (const auto& [from, tos] : layout.edges)
    for (const std::string& to : tos) {
      if (starts_with(from, "sim/") && starts_with(to, "render/")) v.push_back(from + " (simulator) includes " + to);
      const bool renderer = starts_with(from, "render/") && !starts_with(from, "render/app");
      if (renderer && starts_with(to, "sim/") && !frames_library.count(to))
        v.push_back(from + " (renderer) includes " + to + ", outside the frames library");
      if (starts_with(from, "render/app/") && to == "render/app")
        v.push_back(from + " includes the command layer (render/app), which includes it");
      if (starts_with(to, "tests") && from != "tests") v.push_back(from + " includes the tests");
    }
  return v;
}

TEST(Layout, TheSourcesIncludeInOneDirectionFromTheRepositoryRoot) {
  const std::vector<std::string> violations = layout_violations(SPUME_SOURCE_DIR);
  std::string all;
  for (const std::string& v : violations) all += v + "\n";
  EXPECT_TRUE(violations.empty()) << all;
  // The check saw the tree: the command layer reaches the renderer and the simulator.
  const Layout layout = read_layout(SPUME_SOURCE_DIR);
  ASSERT_TRUE(layout.edges.count("render/app"));
  EXPECT_TRUE(layout.edges.at("render/app").count("render/stage"));
  EXPECT_TRUE(layout.edges.at("render/app").count("sim/stage"));
}

// The check itself, on a small tree with each kind of violation planted.
class LayoutCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("spume_layout_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                                        "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    write("sim/core/error.h", "");
    write("sim/fluid/solver.h", "#include \"sim/core/error.h\"\n");
    write("render/gl/pass.h", "#include \"sim/core/error.h\"\n");
    write("render/app/cli/cli_args.h", "");
    write("render/app/commands.h", "#include \"render/app/compare/frame_set.h\"\n#include \"sim/fluid/solver.h\"\n");
    write("render/app/compare/frame_set.h", "#include \"render/app/cli/cli_args.h\"\n");
  }
  void TearDown() override { fs::remove_all(root_); }
  void write(const std::string& name, const std::string& text) {
    fs::create_directories((root_ / name).parent_path());
    std::ofstream(root_ / name) << text;
  }
  std::string violations() {
    std::string all;
    for (const std::string& v : layout_violations(root_)) all += v + "\n";
    return all;
  }
  fs::path root_;
};

TEST_F(LayoutCheck, ACleanTreePasses) { EXPECT_EQ(violations(), ""); }

TEST_F(LayoutCheck, ARendererFileIncludingTheSimulatorFails) {
  write("render/gl/pass.cpp", "#include \"render/gl/pass.h\"\n#include \"sim/fluid/solver.h\"\n");
  EXPECT_NE(violations().find("render/gl (renderer) includes sim/fluid, outside the frames library"), std::string::npos)
      << violations();
}

TEST_F(LayoutCheck, CompareIncludingTheCommandLayerFails) {
  write("render/app/compare/frame_set.cpp", "#include \"render/app/commands.h\"\n");
  const std::string v = violations();
  EXPECT_NE(v.find("render/app/compare includes the command layer"), std::string::npos) << v;
  EXPECT_NE(v.find("render/app -> render/app/compare -> render/app"), std::string::npos) << v;
}

TEST_F(LayoutCheck, TheSimulatorIncludingTheRendererFails) {
  write("sim/fluid/solver.cpp", "#include \"render/gl/pass.h\"\n");
  EXPECT_NE(violations().find("sim/fluid (simulator) includes render/gl"), std::string::npos) << violations();
}

TEST_F(LayoutCheck, RelativeAndShadowedIncludesFail) {
  write("render/app/compare/frame_set.cpp", "#include \"../cli/cli_args.h\"\n");
  write("render/gl/sim/core/error.h", "");
  write("render/gl/pass.cpp", "#include \"sim/core/error.h\"\n");
  const std::string v = violations();
  EXPECT_NE(v.find("frame_set.cpp:1 includes \"../cli/cli_args.h\": not a file named from the repository root"),
            std::string::npos) << v;
  EXPECT_NE(v.find("pass.cpp:1 includes \"sim/core/error.h\": a file beside it answers to the same path"),
            std::string::npos) << v;
}

TEST_F(LayoutCheck, ACycleThroughThreePartsFails) {
  write("sim/core/error.h", "#include \"sim/io/reader.h\"\n");
  write("sim/io/reader.h", "#include \"sim/fluid/solver.h\"\n");
  const std::string v = violations();
  // The cycle may be reported from any of its parts: each of its three steps is named.
  EXPECT_NE(v.find("the parts include in a cycle"), std::string::npos) << v;
  for (const char* step : {"sim/core -> sim/io", "sim/io -> sim/fluid", "sim/fluid -> sim/core"})
    EXPECT_NE(v.find(step), std::string::npos) << step << "\n" << v;
}

}  // namespace
}  // namespace spume
