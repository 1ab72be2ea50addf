// The parts include each other in one direction only (README, Layout): read from the sources.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>

namespace spume {
namespace {

namespace fs = std::filesystem;

// "sim/fluid" -> the top folders of sim/ and render/ it includes ("sim/core", "render/gl", ...).
std::map<std::string, std::set<std::string>> include_edges() {
  const fs::path root = SPUME_SOURCE_DIR;
  std::set<std::string> sim_parts, render_parts;
  for (const auto& e : fs::directory_iterator(root / "sim"))
    if (e.is_directory()) sim_parts.insert(e.path().filename().string());
  for (const auto& e : fs::directory_iterator(root / "render"))
    if (e.is_directory()) render_parts.insert(e.path().filename().string());
  const std::regex include(R"(^#include "([a-z_]+)/)");
  std::map<std::string, std::set<std::string>> edges;
  for (const char* side : {"sim", "render"})
    for (const auto& e : fs::recursive_directory_iterator(root / side)) {
      const std::string ext = e.path().extension().string();
      if (ext != ".h" && ext != ".cpp") continue;
      const fs::path rel = fs::relative(e.path(), root);
      const std::string from = (*rel.begin()).string() + "/" + (*std::next(rel.begin())).string();
      std::ifstream in(e.path());
      for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (!std::regex_search(line, m, include)) continue;
        const std::string folder = m[1];
        // Include paths are rooted at sim/ and render/; render has its own pipeline/ and keys/.
        const bool in_render = std::string(side) == "render" && render_parts.count(folder);
        const std::string to = in_render ? "render/" + folder : sim_parts.count(folder) ? "sim/" + folder
                                                                                         : "render/" + folder;
        if (to != from) edges[from].insert(to);
      }
    }
  return edges;
}

TEST(Layout, NoTwoPartsIncludeEachOtherAndTheRendererSeesOnlyTheFramesLibrary) {
  const auto edges = include_edges();
  ASSERT_FALSE(edges.empty());
  for (const auto& [from, tos] : edges)
    for (const std::string& to : tos) {
      auto back = edges.find(to);
      EXPECT_FALSE(back != edges.end() && back->second.count(from)) << from << " and " << to << " include each other";
      if (from.rfind("sim/", 0) == 0) {
        EXPECT_NE(to.rfind("render/", 0), 0u) << from << " includes " << to;
      }
      const bool renderer = from.rfind("render/", 0) == 0 && from != "render/app";
      if (renderer && to.rfind("sim/", 0) == 0) {
        const std::set<std::string> frames_library = {"sim/core", "sim/io", "sim/geometry", "sim/keys"};
        EXPECT_TRUE(frames_library.count(to)) << from << " includes " << to << ", outside the frames library";
      }
    }
}

}  // namespace
}  // namespace spume
