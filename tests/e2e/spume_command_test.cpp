// The spume command on good and bad input: clear errors naming the key or file, the value and what
// is allowed; non-zero exit; nothing half-written; a run makes every stage's outputs, and a second
// run reuses them (seen in the stage records and the files on disk).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "sim/io/bgeo.h"
#include "sim/io/spume_cache.h"
#include "sim/io/stage_record.h"
#include "tests/support/csv.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_fluids.h"
#include "tests/support/written_files.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::run_spume;

using Result = testing::CommandResult;  // output: stdout and stderr

class SpumeCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir / "cache");
    // Three frames of two blocks closing in (gap 0.02 m at frame 1, overlapping after), as SPlisHSPlasH-style BGEO files numbered from 1.
    for (int k = 1; k <= 3; ++k)
      write_bgeo(dir / "cache" / ("ParticleData_Fluid_" + std::to_string(k) + ".bgeo"),
                 testing::blocks_closing_in(k, 0.2f, 0.3f, Vec3f(2, 0, 0)));
  }

  void write_scene(const std::string& json) { std::ofstream(dir / "scene.json") << json; }
  std::string scene() const { return (dir / "scene.json").string(); }
  std::string out() const { return (dir / "out").string(); }
  bool wrote_anything() const { return fs::exists(dir / "out"); }

  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

TEST_F(SpumeCommand, PostProcessesBgeoFilesWithNoSceneFile) {
  const Result r = run_spume("simulate --quiet --fluid '" + (dir / "cache/ParticleData_Fluid_%d.bgeo").string() +
                             "' --radius 0.02 --out " + out());
  ASSERT_EQ(r.status, 0) << r.output;
  for (int k = 1; k <= 3; ++k) {
    char name[64];
    std::snprintf(name, sizeof name, "diffuse_%04d.spd", k);
    const DiffuseFrame f = read_diffuse_cache(dir / "out/ParticleData_Fluid/diffuse" / name);
    EXPECT_EQ(f.index, k);
    if (k == 1) {
      EXPECT_EQ(f.size(), 0u);  // diffuse material starts empty
    }
  }
  EXPECT_GT(read_diffuse_cache(dir / "out/ParticleData_Fluid/diffuse/diffuse_0003.spd").size(), 0u);
  std::ifstream stats(dir / "out/ParticleData_Fluid/stats.csv");
  std::string header;
  std::getline(stats, header);
  EXPECT_EQ(header.rfind("frame,time,fluid,spray,foam,bubbles,generated,dissolved", 0), 0u) << header;
  EXPECT_EQ(run_spume("info " + (dir / "out/ParticleData_Fluid/diffuse/diffuse_0003.spd").string()).status, 0);
}

// Every scene shipped in scenes/ reads and validates (fluid, solids, diffuse and render keys): render
// gets past the scene and stops only because nothing has been simulated into the empty folder.
TEST_F(SpumeCommand, EveryShippedSceneReadsAndValidates) {
  const fs::path scenes = fs::path(SPUME_TEST_DATA_DIR).parent_path().parent_path() / "scenes";
  int count = 0;
  for (const auto& entry : fs::directory_iterator(scenes)) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    const Result r = run_spume("render " + entry.path().string() + " --out " + (dir / "out").string());
    EXPECT_EQ(r.status, 1) << entry.path() << ": " << r.output;
    EXPECT_NE(r.output.find("fluid caches are not current"), std::string::npos) << entry.path() << ": " << r.output;
  }
  EXPECT_GE(count, 5);
}

TEST_F(SpumeCommand, UnknownSceneKeySuggestsTheClosest) {
  write_scene(R"({"fluid": {"files": "cache/ParticleData_Fluid_%d.bgeo", "radius": 0.02},
                  "diffuse": {"tau_taa": [1, 2]}})");
  const Result r = run_spume("simulate " + scene() + " --out " + out());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("/diffuse/tau_taa"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("did you mean \"tau_ta\""), std::string::npos) << r.output;
  EXPECT_FALSE(wrote_anything());
}

struct BadScene {
  const char* diffuse;   // the `diffuse` object
  const char* expected;  // in the message
};

TEST_F(SpumeCommand, BadParametersAreRejectedNamingKeyValueAndAllowed) {
  const BadScene cases[] = {
      {R"({"tau_ta": [5, 5]})", "/diffuse/tau_ta: min 5 must be below max 5"},
      {R"({"tau_wc": [8, 2]})", "/diffuse/tau_wc: min 8 must be below max 2"},
      {R"({"k_ta": -3})", "/diffuse/k_ta: value -3 is out of range; allowed [0, 1e+06]"},
      {R"({"bubble_drag": "paper", "drag": 1.5})",
       "/diffuse/drag: value 1.5 is out of range for bubble_drag \"paper\"; allowed [0, 1]"},
      {R"({"spray_integrator": "rk4"})", "\"rk4\" is not a choice; allowed: \"exact\", \"euler_cromer\""},
      {R"({"substeps": 0})", "/diffuse/substeps: value 0 is out of range; allowed [1, 64]"},
      {R"({"tau_k": "high"})", "/diffuse/tau_k: expected [min, max]"},
  };
  for (const auto& c : cases) {
    write_scene(std::string(R"({"fluid": {"files": "cache/ParticleData_Fluid_%d.bgeo", "radius": 0.02}, "diffuse": )") +
                c.diffuse + "}");
    const Result r = run_spume("simulate " + scene() + " --out " + out());
    EXPECT_EQ(r.status, 1) << c.diffuse;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.diffuse << "\n" << r.output;
    EXPECT_NE(r.output.find("scene.json"), std::string::npos) << r.output;
    EXPECT_FALSE(wrote_anything()) << c.diffuse;
  }
}

TEST_F(SpumeCommand, BadFluidSettingsAreRejected) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"files": "cache/ParticleData_Fluid_%d.bgeo", "radius": 0})",
       "/fluid/radius: value 0 is out of range; allowed [1e-05, 10]"},
      {R"({"files": "cache/ParticleData_Fluid_%d.bgeo", "radius": 0.02, "support_radius": -1})",
       "/fluid/support_radius: value -1 is out of range; allowed (0, 100]"},
      // No typo of "radius" beside it: no hint.
      {R"({"files": "cache/ParticleData_Fluid_%d.bgeo"})",
       "/fluid/radius: missing: the fluid particle radius r (the particles' spacing is 2 r), in m; it is required\n"},
      {R"({"files": "cache/Nothing_%d.bgeo", "radius": 0.02})", "Nothing_%d.bgeo: no files match"},
  };
  for (const auto& [fluid, expected] : cases) {
    write_scene(std::string(R"({"fluid": )") + fluid + "}");
    const Result r = run_spume("simulate " + scene() + " --out " + out());
    EXPECT_EQ(r.status, 1) << fluid;
    EXPECT_NE(r.output.find(expected), std::string::npos) << fluid << "\n" << r.output;
    EXPECT_FALSE(wrote_anything());
  }
}

TEST_F(SpumeCommand, TruncatedFluidFileIsNamedAndNothingIsHalfWritten) {
  // Frame 2 truncated: the run stops naming the file and leaves no temporary file behind.
  const fs::path bad = dir / "cache/ParticleData_Fluid_2.bgeo";
  fs::resize_file(bad, fs::file_size(bad) / 2);
  write_scene(R"({"fluid": {"files": "cache/ParticleData_Fluid_%d.bgeo", "radius": 0.02}})");
  Result r = run_spume("simulate --quiet " + scene() + " --out " + out());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("ParticleData_Fluid_2.bgeo"), std::string::npos) << r.output;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "out"))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();  // nothing half-written
}

// Hand-written ASCII PLY frames: the second has `second_frame_body` as its vertices.
void write_ply_pair(const fs::path& dir, int second_count, const std::string& second_body) {
  const std::string header = "ply\nformat ascii 1.0\nelement vertex ";
  const std::string props = "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  std::ofstream(dir / "p_1.ply") << header << 2 << props << "0 0 0\n0.01 0 0\n";
  std::ofstream(dir / "p_2.ply") << header << second_count << props << second_body;
}

TEST_F(SpumeCommand, NaNPositionIsRejectedNamingTheParticle) {
  write_ply_pair(dir, 2, "0 0 0\nnan 0 0\n");
  const Result r = run_spume("simulate --quiet --fluid '" + (dir / "p_%d.ply").string() + "' --radius 0.01 --out " + out());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("p_2.ply"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("particle 1"), std::string::npos) << r.output;
}

TEST_F(SpumeCommand, EmptyFrameIsRejectedNamingTheFile) {
  write_ply_pair(dir, 0, "");
  const Result r = run_spume("simulate --quiet --fluid '" + (dir / "p_%d.ply").string() + "' --radius 0.01 --out " + out());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("p_2.ply: holds no fluid particles"), std::string::npos) << r.output;
}

// Width and height from a PNG's IHDR chunk (bytes 16-23, big-endian), read without libpng.
std::pair<int, int> png_size(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char b[24] = {};
  in.read(reinterpret_cast<char*>(b), 24);
  if (!in || b[1] != 'P' || b[2] != 'N' || b[3] != 'G') return {0, 0};
  auto be = [&](int o) { return (b[o] << 24) | (b[o + 1] << 16) | (b[o + 2] << 8) | b[o + 3]; };
  return {be(16), be(20)};
}

// A tiny solver scene: 64 particles falling in a tank, 3 frames, 64 x 36 pixels.
constexpr const char* kTinySolverScene = R"({
  "name": "tiny",
  "fluid": {"source": "solver", "radius": 0.025, "fps": 20, "frames": [0, 2],
            "blocks": [{"min": [0.1, 0.1, 0.1], "max": [0.3, 0.3, 0.3]}]},
  "solids": [{"type": "tank", "min": [0, 0, 0], "max": [0.4, 0.6, 0.4]}],
  "render": {"resolution": [64, 36])";

TEST_F(SpumeCommand, RunSimulatesRendersAndThenReusesEverything) {
  write_scene(std::string(kTinySolverScene) + "}}");
  const fs::path fluid = dir / "out/tiny/fluid", diffuse = dir / "out/tiny/diffuse", frames = dir / "out/tiny/frames";
  Result r = run_spume("run " + scene() + " --out " + out());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* name : {"0000.png", "0001.png", "0002.png"})
    EXPECT_EQ(png_size(dir / "out/tiny/frames" / name), std::make_pair(64, 36)) << name;
  EXPECT_NE(r.output.find("Saved: " + (dir / "out/tiny/frames/0002.png").string()), std::string::npos) << r.output;
  // The fluid solver ran: its record says it made frames 0-2.
  const std::optional<StageRecord> solved = read_stage_record(fluid);
  ASSERT_TRUE(solved);
  EXPECT_EQ(solved->first_frame, 0);
  EXPECT_EQ(solved->last_frame, 2);
  EXPECT_NE(r.output.find("ran: surface reconstruction"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("ran: OSMesa surface pass"), std::string::npos) << r.output;

  // Again: nothing is simulated or rendered (no file of the stages or frames is written again).
  for (const fs::path& folder : {fluid, diffuse, frames}) testing::mark_files(folder);
  const std::string fluid_record = testing::read_file(fluid / "record.json");
  const std::string diffuse_record = testing::read_file(diffuse / "record.json");
  r = run_spume("run " + scene() + " --out " + out());
  ASSERT_EQ(r.status, 0) << r.output;
  for (const fs::path& folder : {fluid, diffuse, frames})
    EXPECT_EQ(testing::written_since_mark(folder), std::vector<std::string>{}) << folder;
  EXPECT_EQ(testing::read_file(fluid / "record.json"), fluid_record);
  EXPECT_EQ(testing::read_file(diffuse / "record.json"), diffuse_record);
  EXPECT_NE(r.output.find("0 frames written, 3 current on disk"), std::string::npos) << r.output;

  // A render key: frames are rendered again, the simulation is reused.
  r = run_spume("run " + scene() + " --out " + out() + " --set render.foam.radius=0.02");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const fs::path& folder : {fluid, diffuse})
    EXPECT_EQ(testing::written_since_mark(folder), std::vector<std::string>{}) << folder;
  EXPECT_EQ(testing::written_since_mark(frames), (std::vector<std::string>{"0000.png", "0001.png", "0002.png"}));
  EXPECT_NE(r.output.find("3 frames written, 0 current on disk"), std::string::npos) << r.output;

  // --overwrite renders the chosen frames even though they are current.
  testing::mark_files(frames);
  r = run_spume("render " + scene() + " --out " + out() + " --set render.foam.radius=0.02 --frames 1-1 --overwrite");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(testing::written_since_mark(frames), std::vector<std::string>{"0001.png"});
  EXPECT_NE(r.output.find("1 frames written, 0 current on disk"), std::string::npos) << r.output;
}

// Caches removed for disk room (the first frames of a long shot) do not stop a render of the frames whose
// caches remain; a frame drawn without its cache is refused naming the file.
TEST_F(SpumeCommand, RenderNeedsOnlyTheCachesOfTheFramesItDraws) {
  write_scene(std::string(kTinySolverScene) + "}}");
  Result r = run_spume("run --quiet " + scene() + " --out " + out());
  ASSERT_EQ(r.status, 0) << r.output;
  const fs::path first_cache = dir / "out/tiny/diffuse/diffuse_0000.spd";
  ASSERT_TRUE(fs::remove(first_cache));
  const fs::path frames = dir / "out/tiny/frames";
  testing::mark_files(frames);
  r = run_spume("render " + scene() + " --out " + out() + " --frames 1-2 --overwrite");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(testing::written_since_mark(frames), (std::vector<std::string>{"0001.png", "0002.png"}));
  // Frame 0's picture can no longer be checked against its cache: it is said to be stale.
  EXPECT_NE(r.output.find("render: 1 other frames on disk are stale"), std::string::npos) << r.output;
  r = run_spume("render --quiet " + scene() + " --out " + out() + " --frames 0-2 --overwrite");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find(first_cache.string() + " is missing"), std::string::npos) << r.output;
}

TEST_F(SpumeCommand, RunLeavesOutWhatTheSceneDoesNotShow) {
  // No surface, no solids drawn, no diffuse type drawn: no reconstruction, no GL, no diffuse stage.
  write_scene(std::string(kTinySolverScene) +
              R"(, "surface": false, "solids": false, "spray": {"radius": 0}, "foam": {"radius": 0},
                 "bubble": {"radius": 0}}})");
  const Result r = run_spume("run " + scene() + " --out " + out());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("surface reconstruction"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("OSMesa"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("volume pass"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("CPU sky and ground"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out/tiny/diffuse"));  // the diffuse stage did not run
  EXPECT_EQ(png_size(dir / "out/tiny/frames/0001.png"), std::make_pair(64, 36));
}

TEST_F(SpumeCommand, RenderNeedsTheCachesAndBadRenderKeysAreNamed) {
  write_scene(std::string(kTinySolverScene) + "}}");
  Result r = run_spume("render " + scene() + " --out " + out());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("out/tiny/fluid: the fluid caches are not current for this scene"), std::string::npos) << r.output;

  const std::pair<const char*, const char*> cases[] = {
      {R"("resolution": [64])", "/render/resolution: expected [width, height] in whole pixels"},
      {R"("integrator": "rk4")", "\"rk4\" is not a choice; allowed: \"exact\", \"march\""},
      {R"("foam": {"radius": -1})", "/render/foam/radius: value -1 is out of range"},
      {R"("spray": {"color": [1, -1, 0]})", "/render/spray/color: value -1 is out of range; allowed [0, 100]"},
      {R"("camera": {"position": [1, 1, 1], "target": [1, 1, 1]})", "/render/camera/target: must differ"},
      {R"("frames": "frames/a.png")", "/render/frames: \"frames/a.png\" needs one frame placeholder"},
      {R"("spp": 0)", "/render/spp: value 0 is out of range"},
  };
  for (const auto& [keys, expected] : cases) {
    write_scene(std::string(kTinySolverScene).replace(std::string(kTinySolverScene).find("\"resolution\""),
                                                      std::string("\"resolution\": [64, 36]").size(), keys) +
                "}}");
    r = run_spume("run --quiet " + scene() + " --out " + out());
    EXPECT_EQ(r.status, 1) << keys;
    EXPECT_NE(r.output.find(expected), std::string::npos) << keys << "\n" << r.output;
  }
}

TEST_F(SpumeCommand, UsageErrorsExitNonZeroWithHelp) {
  EXPECT_EQ(run_spume("").status, 2);
  EXPECT_EQ(run_spume("frobnicate").status, 2);
  Result r = run_spume("simulate --thread 2 x.json");
  EXPECT_EQ(r.status, 2);  // the command line is wrong: a usage error
  EXPECT_NE(r.output.find("did you mean --threads"), std::string::npos) << r.output;
  r = run_spume("simulate " + (dir / "missing.json").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("missing.json: cannot open the scene file (no such file)"), std::string::npos) << r.output;
  write_scene("{\"fluid\": {,}");
  r = run_spume("simulate " + scene());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("scene.json:1: not valid JSON"), std::string::npos) << r.output;
}

// A required key that is missing, next to an unknown key a typo away: the message points at the typo.
TEST_F(SpumeCommand, MissingKeySuggestsTheNearMissUnknownKey) {
  write_scene(R"({"fluid": {"files": "cache/ParticleData_Fluid_%d.bgeo", "radus": 0.02}})");
  const Result r = run_spume("simulate " + scene() + " --out " + out());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("/fluid/radius: missing: the fluid particle radius r (the particles' spacing is 2 r), in m; it is required "
                      "(did you mean \"radus\"? "
                          "it is not a known key)"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(wrote_anything());
}

TEST_F(SpumeCommand, DirectoryAsSceneSaysSoAndListsItsScenes) {
  fs::create_directories(dir / "scenes");
  std::ofstream(dir / "scenes/b.json") << "{}";
  std::ofstream(dir / "scenes/a.json") << "{}";
  std::ofstream(dir / "scenes/notes.txt") << "not a scene";
  Result r = run_spume("run " + (dir / "scenes").string() + " --out " + out());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find((dir / "scenes").string() + ": is a directory, not a scene file (give one SCENE.json); "
                          "scene files in it: " + (dir / "scenes/a.json").string() + " " +
                          (dir / "scenes/b.json").string() + "\n"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("not valid JSON"), std::string::npos) << r.output;
  r = run_spume("simulate " + (dir / "cache").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(": is a directory, not a scene file (give one SCENE.json); it holds no .json file"),
            std::string::npos)
      << r.output;
}

// Houdini's .bgeo.sc is read (io_houdini_test.cpp); a file so named that is not one is refused, naming the
// file and what it lacks, by the scene commands and by info; so is a truncated binary JSON under another name.
TEST_F(SpumeCommand, BrokenHoudiniFilesAreRefusedNamingTheFile) {
  for (int k = 1; k <= 2; ++k) std::ofstream(dir / "cache" / ("sc_" + std::to_string(k) + ".bgeo.sc")) << "compressed";
  write_scene(R"({"fluid": {"files": "cache/sc_%d.bgeo.sc", "radius": 0.02}})");
  Result r = run_spume("simulate --quiet " + scene() + " --out " + out());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("sc_1.bgeo.sc: not a .bgeo.sc file: it must start with 'scf1'"), std::string::npos) << r.output;
  r = run_spume("info " + (dir / "cache/sc_2.bgeo.sc").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("sc_2.bgeo.sc: not a .bgeo.sc file: it must start with 'scf1'"), std::string::npos) << r.output;
  std::ofstream(dir / "cache/frame.hgeo", std::ios::binary) << std::string("\x7fNSJb[", 6);
  r = run_spume("info " + (dir / "cache/frame.hgeo").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("frame.hgeo: truncated"), std::string::npos) << r.output;
}

TEST_F(SpumeCommand, EmissionBeyondThePerParticleCapIsCountedAndWarned) {
  // The blocks meet at 4 m/s; with k_ta = 10^6/s and clamps that any approach saturates, Eq. 8 asks
  // 10^6 x 0.02 s = 20000 new particles of each facing particle per step, beyond the 4,095 a diffuse
  // id can number. The run says so once and stats.csv counts the cut (the budget keeps it small).
  write_scene(R"({"fluid": {"files": "cache/ParticleData_Fluid_%d.bgeo", "radius": 0.02},
                  "diffuse": {"k_ta": 1000000, "k_wc": 0, "tau_ta": [0.01, 0.02], "tau_k": [0.0001, 0.0002],
                              "max_particles": 1000}})");
  const Result r = run_spume("simulate " + scene() + " --out " + out());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("more than 4095 new diffuse particles in one step"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("stats.csv 'capped'"), std::string::npos) << r.output;
  const auto stats = testing::read_csv(dir / "out/scene/stats.csv");
  ASSERT_FALSE(stats.empty());
  ASSERT_EQ(std::vector<std::string>(stats[0].begin(), stats[0].begin() + std::min<size_t>(stats[0].size(), 12)),
            (std::vector<std::string>{"frame", "time", "fluid", "spray", "foam", "bubbles", "generated", "dissolved",
                                      "removed", "landed", "dropped", "capped"}));
  const double capped = testing::column_sum(stats, "capped");
  // Each facing particle at full potential loses 20000 - 4095 = 15905 per step.
  EXPECT_GT(capped, 15905u);
}

}  // namespace
}  // namespace spume
