// The farm side of the spume command on a tiny solver scene (tests/data/farm_tiny.json): chunks
// rendered by separate processes are byte-identical to one render, renders resume, a failed frame
// is named, progress is one line per frame in logs, and `farm slurm` writes its scripts (a
// simulation job only when the caches are stale). The real cluster: slurm_farm_test.sh.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <unistd.h>

#include "tests/support/files.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"

namespace {

namespace fs = std::filesystem;

using Result = spume::testing::CommandResult;  // output: stdout; err: stderr

// Runs spume with stdout and stderr captured separately (both are pipes, not terminals).
Result spume_apart(const std::string& arguments, const std::string& environment = "") {
  return spume::testing::run_spume(arguments, spume::testing::SpumeOptions::stderr_apart(environment));
}

int count_lines_starting(const std::string& text, const std::string& prefix) {
  std::istringstream in(text);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind(prefix, 0) == 0;
  return n;
}

const std::string kScene = std::string(SPUME_TEST_DATA_DIR) + "/farm_tiny.json";
constexpr int kFrames = 8;

// One simulation for the suite; each test renders to its own frames folder (render.frames).
class FarmCommand : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    temp = std::make_unique<spume::testing::TempDir>("FarmCommand");
    root = temp->path;
    const Result r = spume_apart("simulate " + kScene + " --quiet --out " + (root / "out").string());
    ASSERT_EQ(r.status, 0) << r.err;
  }
  static void TearDownTestSuite() { temp.reset(); }

  std::string name() const { return ::testing::UnitTest::GetInstance()->current_test_info()->name(); }
  // Scene, output root and this test's frames folder.
  std::string args() const {
    return kScene + " --out " + (root / "out").string() + " --set render.frames=" + name() + "/%04d.png";
  }
  fs::path frames_dir() const { return root / "out/farm_tiny" / name(); }
  fs::path frame(int f) const {
    char file[16];
    std::snprintf(file, sizeof file, "%04d.png", f);
    return frames_dir() / file;
  }

  static std::unique_ptr<spume::testing::TempDir> temp;
  static fs::path root;
};
std::unique_ptr<spume::testing::TempDir> FarmCommand::temp;
fs::path FarmCommand::root;

TEST_F(FarmCommand, ChunksPrintOneFrameSpecPerLine) {
  Result r = spume_apart("farm chunks " + args() + " --chunk 3");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.output, "0-2\n3-5\n6-7\n");
  r = spume_apart("farm chunks " + args() + " --chunk 1 --frames 5-99:2");  // clamped to the scene's 0-7
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.output, "5\n7\n");
  r = spume_apart("farm chunks " + args());
  EXPECT_EQ(r.status, 2);  // a usage error
  EXPECT_NE(r.err.find("--chunk N"), std::string::npos) << r.err;
}

TEST_F(FarmCommand, ChunksRenderedByOtherProcessesAreByteIdenticalToOneRender) {
  const Result whole = spume_apart("render " + args());
  ASSERT_EQ(whole.status, 0) << whole.err;
  EXPECT_EQ(count_lines_starting(whole.output, "Saved: "), kFrames) << whole.output;
  std::vector<std::string> reference;
  for (int f = 0; f < kFrames; ++f) reference.push_back(spume::testing::read_file(frame(f)));
  fs::remove_all(frames_dir());

  const Result chunks = spume_apart("farm chunks " + args() + " --chunk 3");
  ASSERT_EQ(chunks.status, 0) << chunks.err;
  std::istringstream specs(chunks.output);
  int saved = 0;
  for (std::string spec; std::getline(specs, spec);) {
    const Result part = spume_apart("render " + args() + " --frames " + spec);
    ASSERT_EQ(part.status, 0) << part.err;
    saved += count_lines_starting(part.output, "Saved: ");
  }
  EXPECT_EQ(saved, kFrames);
  for (int f = 0; f < kFrames; ++f) EXPECT_EQ(spume::testing::read_file(frame(f)), reference[size_t(f)]) << "frame " << f;
}

TEST_F(FarmCommand, RenderResumesWithOnlyMissingOrBrokenFrames) {
  ASSERT_EQ(spume_apart("render " + args()).status, 0);
  fs::remove(frame(2));
  fs::remove(frame(6));
  std::ofstream(frame(4), std::ios::trunc) << "half a png";  // e.g. a copy cut short
  Result r = spume_apart("render " + args());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.output, "Saved: " + frame(2).string() + "\nSaved: " + frame(4).string() + "\nSaved: " +
                       frame(6).string() + "\n");
  EXPECT_EQ(count_lines_starting(r.output, "Saved: "), 3);
  r = spume_apart("render " + args() + " --overwrite --frames 1-3");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(count_lines_starting(r.output, "Saved: "), 3);
  for (const auto& entry : fs::directory_iterator(frames_dir()))
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST_F(FarmCommand, ProgressIsOneParseableLinePerFrameInLogs) {
  const Result r = spume_apart("render " + args());
  ASSERT_EQ(r.status, 0) << r.err;
  for (int k = 1; k <= kFrames; ++k) {
    const std::string line = "render farm_tiny: frame " + std::to_string(k) + "/" + std::to_string(kFrames) + "  ";
    EXPECT_EQ(count_lines_starting(r.err, line), 1) << line << "\n" << r.err;
  }
  EXPECT_EQ(count_lines_starting(r.err, "render farm_tiny: frame "), kFrames) << r.err;
  EXPECT_NE(r.err.find(" eta "), std::string::npos) << r.err;
}

TEST_F(FarmCommand, FailedFrameExitsNonZeroAndNamesTheFrame) {
  const fs::path out = root / name();
  fs::create_directories(out);
  fs::copy(root / "out", out, fs::copy_options::recursive);
  // Damage the middle of frame 5's cache (its size and CRC trailer stay, so only reading it tells).
  const fs::path cache = out / "farm_tiny/diffuse/diffuse_0005.spd";
  {
    std::fstream f(cache, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x7f');
  }
  Result r = spume_apart("render " + kScene + " --out " + out.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("error: frame 5: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("diffuse_0005.spd"), std::string::npos) << r.err;
  EXPECT_EQ(count_lines_starting(r.output, "Saved: "), 5) << r.output;  // frames 0-4 are kept for the resume

  // A missing cache is found before anything is rendered, and named.
  fs::remove(cache);
  r = spume_apart("render " + kScene + " --out " + out.string() + " --overwrite");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("diffuse_0005.spd is missing"), std::string::npos) << r.err;
  EXPECT_EQ(count_lines_starting(r.output, "Saved: "), 0) << r.output;
}

TEST_F(FarmCommand, SlurmScriptsHaveASimulationJobOnlyWhenTheCachesAreStale) {
  const fs::path fresh = root / name();
  Result r = spume_apart("farm slurm " + kScene + " --out " + fresh.string() + " --chunk 2 --partition fx");
  ASSERT_EQ(r.status, 0) << r.err;
  const fs::path farm = fresh / "farm_tiny/farm";
  EXPECT_EQ(r.output, "Saved: " + (farm / "simulate.sbatch").string() + "\nSaved: " + (farm / "render.sbatch").string() +
                       "\nSaved: " + (farm / "submit.sh").string() + "\n");
  const std::string render = spume::testing::read_file(farm / "render.sbatch");
  EXPECT_NE(render.find("#SBATCH --array=0-3\n"), std::string::npos) << render;
  EXPECT_NE(render.find("#SBATCH --partition=fx\n"), std::string::npos) << render;
  EXPECT_NE(render.find("'render' '" + kScene + "' '--out' '" + fresh.string() + "'"), std::string::npos) << render;
  EXPECT_NE(spume::testing::read_file(farm / "submit.sh").find("--dependency=afterok:"), std::string::npos);

  r = spume_apart("farm slurm " + args() + " --chunk 2");  // the suite's caches are current
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(root / "out/farm_tiny/farm/simulate.sbatch"));
  EXPECT_NE(r.err.find("no simulation job"), std::string::npos) << r.err;
  EXPECT_EQ(spume::testing::read_file(root / "out/farm_tiny/farm/submit.sh").find("dependency"), std::string::npos);
}

TEST_F(FarmCommand, SubmitWithoutSbatchIsAClearError) {
  const Result r = spume_apart("farm slurm " + args() + " --chunk 2 --submit", "PATH=/nonexistent");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("sbatch is not on PATH"), std::string::npos) << r.err;
}

TEST_F(FarmCommand, SimulateFramesMustBeOneUnbrokenRange) {
  Result r = spume_apart("simulate " + args() + " --frames 0-6:2");
  EXPECT_EQ(r.status, 2);  // usage errors
  EXPECT_NE(r.err.find("--frames: \"0-6:2\" is not one unbroken range"), std::string::npos) << r.err;
  r = spume_apart("simulate " + args() + " --frames 0-x");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("accepted forms"), std::string::npos) << r.err;
}

}  // namespace
