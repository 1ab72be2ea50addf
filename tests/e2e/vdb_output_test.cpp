// output.vdb (`spume simulate --vdb`) through the binary: one .vdb per diffuse frame holding that
// frame's particles, nothing rewritten on a rerun, rewritten when the caches change, removed when the
// option goes off (without re-simulating), none when never asked for, and the same bytes for 1 and 2
// threads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include <openvdb/openvdb.h>
#include <openvdb/io/File.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>

#include "sim/io/bgeo.h"
#include "sim/io/spume_cache.h"
#include "tests/support/files.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_fluids.h"
#include "tests/support/written_files.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::run_spume;

// The ids of the points in a .vdb, read with OpenVDB.
std::multiset<uint64_t> vdb_ids(const fs::path& path) {
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.open();
  const auto grid = openvdb::gridPtrCast<openvdb::points::PointDataGrid>(file.readGrid("points"));
  EXPECT_TRUE(grid) << path;
  std::multiset<uint64_t> ids;
  if (!grid) return ids;
  for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf) {
    if (!leaf->hasAttribute("id")) continue;
    openvdb::points::AttributeHandle<int64_t> id(leaf->constAttributeArray("id"));
    for (auto index = leaf->beginIndexOn(); index; ++index) ids.insert(uint64_t(id.get(*index)));
  }
  return ids;
}

// Eight BGEO frames of two blocks of water thrown at each other in a tank (as in provenance_test).
class VdbOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir / "cache");
    for (int k = 1; k <= 8; ++k)
      write_bgeo(dir / "cache" / ("fluid_" + std::to_string(k) + ".bgeo"),
                 testing::blocks_closing_in(k, 0.16f, 0.5f, Vec3f(2.0f, 1, 0)));
    std::ofstream(dir / "scene.json") << R"({
      "name": "blocks",
      "fluid": {"files": "cache/fluid_%d.bgeo", "radius": 0.02},
      "solids": [{"type": "tank", "min": [-0.1, -0.02, -0.1], "max": [0.6, 0.6, 0.3]}],
      "diffuse": {"k_ta": 2000, "k_wc": 2000}
    })";
  }
  std::string args(const std::string& more = "", const std::string& out_dir = "out") const {
    return (dir / "scene.json").string() + " --quiet --out " + (dir / out_dir).string() + " " + more;
  }
  fs::path out(const std::string& relative, const std::string& out_dir = "out") const {
    return dir / out_dir / "blocks" / relative;
  }
  static std::string numbered(int k, const char* ext) {
    char name[32];
    std::snprintf(name, sizeof name, "diffuse_%04d%s", k, ext);
    return name;
  }
  // Each .vdb holds exactly the particles of the .spd beside it.
  void expect_vdb_matches_caches(const std::string& out_dir = "out") const {
    size_t total = 0;
    for (int k = 1; k <= 8; ++k) {
      const DiffuseFrame spd = read_diffuse_cache(out("diffuse/" + numbered(k, ".spd"), out_dir));
      const std::multiset<uint64_t> expected(spd.ids.begin(), spd.ids.end());
      EXPECT_EQ(vdb_ids(out("diffuse_vdb/" + numbered(k, ".vdb"), out_dir)), expected) << "frame " << k;
      total += spd.size();
    }
    EXPECT_GT(total, 100u) << "the scene should make diffuse particles";
  }
  size_t vdb_files(const std::string& out_dir = "out") const {
    size_t n = 0;
    if (!fs::is_directory(out("diffuse_vdb", out_dir))) return 0;
    for (const auto& e : fs::directory_iterator(out("diffuse_vdb", out_dir))) n += e.path().extension() == ".vdb";
    return n;
  }

  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

TEST_F(VdbOutput, OneVdbPerFrameNotRewrittenOnARerunRemovedWhenOff) {
  CommandResult r = run_spume("simulate " + args("--vdb"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(vdb_files(), 8u);
  expect_vdb_matches_caches();
  EXPECT_TRUE(fs::exists(out("diffuse_vdb/record.json")));

  testing::mark_files(out("diffuse_vdb"));
  testing::mark_files(out("diffuse"));
  r = run_spume("simulate " + args("--set output.vdb=true"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(testing::written_since_mark(out("diffuse_vdb")), std::vector<std::string>{});

  // Other diffuse keys: the caches change, and every .vdb made from a changed cache is written again.
  r = run_spume("simulate " + args("--vdb --set diffuse.seed=7"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(testing::written_since_mark(out("diffuse_vdb")).empty());
  expect_vdb_matches_caches();

  // Off: the .vdb files and their record go, and nothing is simulated again.
  testing::mark_files(out("diffuse"));
  r = run_spume("simulate " + args("--set diffuse.seed=7"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(vdb_files(), 0u);
  EXPECT_FALSE(fs::exists(out("diffuse_vdb")));
  EXPECT_EQ(testing::written_since_mark(out("diffuse")), std::vector<std::string>{});
}

TEST_F(VdbOutput, NoneUnlessAskedAndTurningItOnSimulatesNothing) {
  CommandResult r = run_spume("simulate " + args());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(out("diffuse_vdb")));
  testing::mark_files(out("diffuse"));
  r = run_spume("simulate " + args("--vdb"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(testing::written_since_mark(out("diffuse")), std::vector<std::string>{}) << "the diffuse stage ran again";
  EXPECT_EQ(vdb_files(), 8u);
  expect_vdb_matches_caches();
}

TEST_F(VdbOutput, AShorterRangeKeepsTheOthersOnlyWhileTheirCachesAreUnchanged) {
  ASSERT_EQ(run_spume("simulate " + args("--vdb")).status, 0);
  testing::mark_files(out("diffuse_vdb"));
  CommandResult r = run_spume("simulate " + args("--vdb --frames 1-5"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(vdb_files(), 8u);
  EXPECT_EQ(testing::written_since_mark(out("diffuse_vdb")), std::vector<std::string>{});
  // New keys over frames 1-5: their caches change, and frames 6-8 (made from the old caches, which
  // no longer continue these) are noticed once their .spd changes too.
  r = run_spume("simulate " + args("--vdb --frames 1-5 --set diffuse.seed=3"));
  ASSERT_EQ(r.status, 0) << r.output;
  for (int k = 1; k <= 5; ++k) {
    const DiffuseFrame spd = read_diffuse_cache(out("diffuse/" + numbered(k, ".spd")));
    EXPECT_EQ(vdb_ids(out("diffuse_vdb/" + numbered(k, ".vdb"))), std::multiset<uint64_t>(spd.ids.begin(), spd.ids.end()));
  }
  std::filesystem::remove(out("diffuse/" + numbered(7, ".spd")));
  r = run_spume("simulate " + args("--vdb --frames 1-5 --set diffuse.seed=3"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(out("diffuse_vdb/" + numbered(7, ".vdb"))));
  EXPECT_TRUE(fs::exists(out("diffuse_vdb/" + numbered(6, ".vdb"))));
}

TEST_F(VdbOutput, AFarmRunsTheSimulationJobWhileTheVdbFilesAreMissing) {
  ASSERT_EQ(run_spume("simulate " + args()).status, 0);
  const std::string farm = "farm slurm " + (dir / "scene.json").string() + " --out " + (dir / "out").string() +
                           " --chunk 4 --set output.vdb=true";
  CommandResult r = run_spume(farm);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("a simulation job runs first"), std::string::npos) << r.output;
  ASSERT_EQ(run_spume("simulate " + args("--vdb")).status, 0);
  r = run_spume(farm);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("no simulation job"), std::string::npos) << r.output;
}

TEST_F(VdbOutput, SameBytesForOneAndTwoThreads) {
  ASSERT_EQ(run_spume("simulate " + args("--vdb --threads 1", "one")).status, 0);
  ASSERT_EQ(run_spume("simulate " + args("--vdb --threads 2", "two")).status, 0);
  for (int k = 1; k <= 8; ++k) {
    const std::string name = "diffuse_vdb/" + numbered(k, ".vdb");
    EXPECT_TRUE(testing::read_file(out(name, "one")) == testing::read_file(out(name, "two"))) << name;
  }
}

}  // namespace
}  // namespace spume
