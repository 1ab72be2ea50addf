// End to end: `spume report --quick --only surface,stability` writes its CSVs, plots and report.md
// with sane values; bad options are clear errors.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct Result {
  int status = -1;
  std::string output;
};

Result run_spume(const std::string& arguments) {
  const std::string command = std::string(SPUME_BINARY) + " " + arguments + " 2>&1";
  Result r;
  FILE* pipe = popen(command.c_str(), "r");
  std::array<char, 4096> buffer;
  while (size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::vector<std::vector<std::string>> read_csv(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(ReportCommand, QuickSurfaceAndStabilityWriteSaneFiles) {
  const fs::path out = fs::temp_directory_path() / ("spume_report_e2e_" + std::to_string(getpid()));
  fs::remove_all(out);
  // A tiny scene (the two studies do not simulate it; the command still takes the positional).
  fs::create_directories(out);
  std::ofstream(out / "tiny.json") << R"({"fluid": {"source": "solver", "radius": 0.02, "frames": [0, 2],
    "blocks": [{"min": [0, 0, 0], "max": [0.2, 0.2, 0.2]}]}, "solids": [{"type": "tank", "min": [0, 0, 0], "max": [0.4, 0.4, 0.4]}]})";
  const Result ok = run_spume("report " + (out / "tiny.json").string() + " --quick --only surface,stability --quiet --out " +
                              out.string());
  ASSERT_EQ(ok.status, 0) << ok.output;
  const fs::path dir = out / "report";
  for (const char* name : {"surface.csv", "surface.png", "surface.gp", "stability.csv", "stability.png", "report.md"})
    EXPECT_TRUE(fs::is_regular_file(dir / name)) << name;

  const auto surface = read_csv(dir / "surface.csv");
  ASSERT_EQ(surface.size(), 1u + 2 * 3) << "ball and box at 3 cell sizes";
  ASSERT_EQ(surface[0][0], "shape");
  ASSERT_EQ(surface[0][6], "mean_abs_distance_r");
  for (size_t i = 1; i < surface.size(); ++i) {
    const double ms = std::stod(surface[i][5]), mean = std::stod(surface[i][6]), max = std::stod(surface[i][8]);
    EXPECT_GT(ms, 0.0);
    // The mesh lies on the particles' extent to within a particle radius (tests/render/surface_*).
    EXPECT_GT(mean, 0.0);
    EXPECT_LT(mean, 0.5) << surface[i][0] << " cell " << surface[i][2];
    EXPECT_LE(mean, max);
    EXPECT_LT(max, 1.5);
    EXPECT_GT(std::stoul(surface[i][4]), 100u);
  }
  const auto stability = read_csv(dir / "stability.csv");
  ASSERT_GT(stability.size(), 10u);
  for (size_t i = 1; i < stability.size(); ++i) EXPECT_TRUE(stability[i][2] == "pass" || stability[i][2] == "FAIL");

  std::ifstream md(dir / "report.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("![4. Surface reconstruction"), std::string::npos);
  EXPECT_NE(text.str().find("| ball | "), std::string::npos);
  EXPECT_NE(text.str().find("cases pass"), std::string::npos);
  // Nothing temporary is left.
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().filename().string()[0], '.') << e.path();
  fs::remove_all(out);
}

TEST(ReportCommand, UnknownStudyIsAnErrorNamingTheValueAndTheAllowedOnes) {
  const Result r = run_spume("report --only surface,foam --quiet --out /tmp/spume_report_never");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("--only: \"foam\" is not a study; allowed: render,diffuse,fluid,surface,stability"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists("/tmp/spume_report_never"));
}

TEST(ReportCommand, MissingSceneIsAnErrorBeforeAnyWork) {
  const Result r = run_spume("report /nonexistent/scene.json --only render --quiet --out /tmp/spume_report_never");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("/nonexistent/scene.json: no such scene file"), std::string::npos) << r.output;
}

}  // namespace
