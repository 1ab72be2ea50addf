// The exports (`spume simulate --vdb`, `--bgeo`, `spume run --fog`) through the binary: one file per diffuse frame holding
// that frame's particles, nothing rewritten on a rerun, rewritten when the caches change, removed when
// the option goes off (without re-simulating), none when never asked for, the same bytes for 1 and 2
// threads; and never an earlier run's files beside the current run's (io/frame_export.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <openvdb/openvdb.h>
#include <openvdb/io/File.h>
#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>

#include "sim/io/bgeo.h"
#include "sim/io/spume_cache.h"
#include "tests/support/blocks_scene.h"
#include "tests/support/files.h"
#include "tests/support/run_command.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text.h"
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

// Each point's age, life and lifetime by id, read with OpenVDB's own API.
struct Ages {
  float age, life, lifetime;
};
std::map<uint64_t, Ages> vdb_ages(const fs::path& path) {
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.open();
  const auto grid = openvdb::gridPtrCast<openvdb::points::PointDataGrid>(file.readGrid("points"));
  std::map<uint64_t, Ages> ages;
  if (!grid) return ages;
  for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf) {
    openvdb::points::AttributeHandle<int64_t> id(leaf->constAttributeArray("id"));
    openvdb::points::AttributeHandle<float> age(leaf->constAttributeArray("age")), life(leaf->constAttributeArray("life")),
        lifetime(leaf->constAttributeArray("lifetime"));
    for (auto index = leaf->beginIndexOn(); index; ++index)
      ages[uint64_t(id.get(*index))] = {age.get(*index), life.get(*index), lifetime.get(*index)};
  }
  return ages;
}

// The blocks scene of tests/support/blocks_scene.h (as in provenance_test).
class Exports : public ::testing::Test {
 protected:
  void SetUp() override { testing::write_blocks_scene(dir); }
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

TEST_F(Exports, OneVdbPerFrameNotRewrittenOnARerunRemovedWhenOff) {
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

TEST_F(Exports, NoneUnlessAskedAndTurningItOnSimulatesNothing) {
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

// The issue's case: frames 1-8 exported, then frames 1-4 with other keys. The caches of 5-8 are the
// earlier run's, so their .vdb and .bgeo go, and the log says so; 1-4 hold the new caches' particles.
TEST_F(Exports, AnotherRunOverAShorterRangeLeavesOnlyItsOwnFrames) {
  ASSERT_EQ(run_spume("simulate " + args("--vdb --bgeo")).status, 0);
  // The same keys over frames 1-4: the caches of 1-8 are current and reused, and so are the exports.
  testing::mark_files(out("diffuse_vdb"));
  CommandResult r = run_spume("simulate " + args("--vdb --bgeo --frames 1-4"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(vdb_files(), 8u);
  EXPECT_EQ(testing::written_since_mark(out("diffuse_vdb")), std::vector<std::string>{});
  // Other keys over frames 1-4.
  r = run_spume("simulate " + args("--vdb --bgeo --frames 1-4 --set diffuse.seed=3").replace(args().find("--quiet"), 7, ""));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(testing::contains(r.output, "diffuse_vdb: removed 4 .vdb files of frames 5-8 (frames of an earlier run: "
                                          "this run's caches are frames 1-4)")) << r.output;
  EXPECT_TRUE(testing::contains(r.output, "diffuse_bgeo: removed 4 .bgeo files of frames 5-8")) << r.output;
  EXPECT_EQ(vdb_files(), 4u);
  for (int k = 1; k <= 8; ++k) {
    EXPECT_EQ(fs::exists(out("diffuse_bgeo/" + numbered(k, ".bgeo"))), k <= 4) << k;
    if (k > 4) continue;
    const DiffuseFrame spd = read_diffuse_cache(out("diffuse/" + numbered(k, ".spd")));
    const std::multiset<uint64_t> expected(spd.ids.begin(), spd.ids.end());
    EXPECT_EQ(vdb_ids(out("diffuse_vdb/" + numbered(k, ".vdb"))), expected) << k;
    const DiffuseFrame bgeo = read_bgeo_diffuse(out("diffuse_bgeo/" + numbered(k, ".bgeo")));
    EXPECT_EQ(std::multiset<uint64_t>(bgeo.ids.begin(), bgeo.ids.end()), expected) << k;
  }
}

// The issue's other case: BGEO on 8 frames, then a rerun with other keys and no --bgeo. The .bgeo
// files of the earlier run go (the log says why), and asking for them again writes them from the
// caches without simulating again.
TEST_F(Exports, BgeoFilesGoWhenARunDoesNotAskForThemAndComeBackWithoutSimulating) {
  ASSERT_EQ(run_spume("simulate " + args("--bgeo")).status, 0);
  for (int k = 1; k <= 8; ++k) EXPECT_TRUE(fs::exists(out("diffuse_bgeo/" + numbered(k, ".bgeo")))) << k;
  CommandResult r = run_spume("simulate " + args("--set diffuse.seed=5").replace(args().find("--quiet"), 7, ""));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(testing::contains(r.output, "diffuse_bgeo: removed 8 .bgeo files of frames 1-8 (output.bgeo is off)"))
      << r.output;
  EXPECT_FALSE(fs::exists(out("diffuse_bgeo")));
  testing::mark_files(out("diffuse"));
  r = run_spume("simulate " + args("--bgeo --set diffuse.seed=5"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(testing::written_since_mark(out("diffuse")), std::vector<std::string>{}) << "the diffuse stage ran again";
  for (int k = 1; k <= 8; ++k) {
    const DiffuseFrame spd = read_diffuse_cache(out("diffuse/" + numbered(k, ".spd")));
    const DiffuseFrame bgeo = read_bgeo_diffuse(out("diffuse_bgeo/" + numbered(k, ".bgeo")));
    EXPECT_EQ(std::multiset<uint64_t>(bgeo.ids.begin(), bgeo.ids.end()),
              std::multiset<uint64_t>(spd.ids.begin(), spd.ids.end())) << k;
  }
}

// Exports are no part of what the render depends on: `simulate --bgeo --vdb`, then `render` of the scene
// as written (no export keys) renders the caches instead of refusing them as made with other keys.
TEST_F(Exports, RenderAfterAnExportUsesTheCaches) {
  ASSERT_EQ(run_spume("simulate " + args("--bgeo --vdb")).status, 0);
  const CommandResult r = run_spume("render " + args("--set 'render.resolution=[64,36]' --frames 8"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(testing::contains(r.output, "output.")) << r.output;
}

// Fog volumes (`run --fog`, io/fog_volumes.h), read with OpenVDB's Python module (Debian's
// python3-openvdb): one file per diffuse frame, each type's grid holding the volume of its particles
// as drawn (N 4/3 pi r^3 at the render's radii), density their sum; `spume info` describes them.
// Turning the fog on draws no PNG frame again; turning it off removes its files.
TEST_F(Exports, FogVolumesHoldEachTypesParticleVolumeReadByOpenVdbsPython) {
  const std::string look = "--set 'render.resolution=[64,36]' --set render.spray.radius=0.006 "
                           "--set render.foam.radius=0.03 --set render.bubble.radius=0.01 ";
  ASSERT_EQ(run_spume("run " + args(look)).status, 0);
  testing::mark_files(out("frames"));
  CommandResult r = run_spume("run " + args(look + "--fog 0.02"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(testing::written_since_mark(out("frames")), std::vector<std::string>{}) << "frames drawn again";

  testing::write_file(dir / "fog.py", R"(import sys, pyopenvdb as vdb
for path in sys.argv[1:]:
    grids, meta = vdb.readAll(path)
    for g in grids:
        if g.name != 'v':
            s = g.transform.voxelSize()[0]
            print(path[-8:-4], g.name, g.gridClass.replace(' ', '_'), repr(sum(i.value * i.count for i in g.citerOnValues()) * s ** 3))
)");
  std::string files;
  for (int k = 1; k <= 8; ++k) files += " " + out(str("diffuse_fog/fog_000", k, ".vdb")).string();
  const CommandResult py = testing::run_command("/usr/bin/python3 " + (dir / "fog.py").string() + files + " 2>&1");
  ASSERT_EQ(py.status, 0) << py.output;
  std::map<std::pair<int, std::string>, double> volume;
  std::istringstream lines(py.output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    int frame = 0;
    std::string grid, grid_class;
    double v = 0.0;
    ASSERT_TRUE(fields >> frame >> grid >> grid_class >> v) << line;
    EXPECT_EQ(grid_class, "fog_volume") << line;
    volume[{frame, grid}] = v;
  }
  const double radius[3] = {0.006, 0.03, 0.01};
  size_t particles = 0;
  for (int k = 1; k <= 8; ++k) {
    const DiffuseFrame spd = read_diffuse_cache(out("diffuse/" + numbered(k, ".spd")));
    const auto count = spd.count_by_type();
    double all = 0.0;
    for (int t = 0; t < kDiffuseTypeCount; ++t) {
      const double expected = double(count[size_t(t)]) * 4.0 / 3.0 * M_PI * std::pow(radius[t], 3);
      const double written = volume[{k, to_string(DiffuseType(t))}];
      EXPECT_NEAR(written, expected, 1e-4 * expected + 1e-12)
          << "frame " << k << ", " << to_string(DiffuseType(t));
      all += expected;
    }
    const double density = volume[{k, "density"}];
    EXPECT_NEAR(density, all, 1e-4 * all + 1e-12) << "frame " << k;
    particles += spd.size();
  }
  EXPECT_GT(particles, 100u);
  // spume reads its own fog export back: info names it and gives each grid's integral.
  const CommandResult info = run_spume("info " + out("diffuse_fog/fog_0008.vdb").string());
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_TRUE(testing::contains(info.output, "content: spume fog volumes (output.fog), frame 8")) << info.output;
  EXPECT_TRUE(testing::contains(info.output, "'density': fog volume, ")) << info.output;
  const CommandResult folder = run_spume("info " + out("").string());
  EXPECT_TRUE(testing::contains(folder.output, "fog volumes export (diffuse_fog/): frames 1-8")) << folder.output;

  testing::mark_files(out("frames"));
  r = run_spume("render " + args(look).replace(args().find("--quiet"), 7, ""));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(testing::contains(r.output, "diffuse_fog: removed 8 .vdb files of frames 1-8 (output.fog is off)"))
      << r.output;
  EXPECT_FALSE(fs::exists(out("diffuse_fog")));
  EXPECT_EQ(testing::written_since_mark(out("frames")), std::vector<std::string>{}) << "frames drawn again";
}

// The issue's staleness case for fog: simulating again with other keys rewrites the fog from the new
// caches (foam's integral is the new count's volume, read by spume info), and a simulation without
// output.fog removes it, as it removes the other exports.
TEST_F(Exports, ASimulationKeepsTheFogInLineWithTheCachesItMakes) {
  const std::string look = "--set 'render.resolution=[64,36]' --set render.foam.radius=0.03 ";
  ASSERT_EQ(run_spume("run " + args(look + "--fog 0.02")).status, 0);
  testing::mark_files(out("diffuse_fog"));
  CommandResult r = run_spume("simulate " + args(look + "--set output.fog=0.02 --set diffuse.seed=9"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(testing::written_since_mark(out("diffuse_fog")).empty()) << "fog left from the earlier caches";
  const size_t foam = read_diffuse_cache(out("diffuse/" + numbered(8, ".spd"))).count_by_type()[size_t(DiffuseType::Foam)];
  ASSERT_GT(foam, 0u);
  const CommandResult info = run_spume("info " + out("diffuse_fog/fog_0008.vdb").string());
  const size_t at = info.output.find("'foam': fog volume, ");
  ASSERT_NE(at, std::string::npos) << info.output;
  const size_t integral = info.output.find("integral ", at);
  ASSERT_NE(integral, std::string::npos) << info.output;
  const double expected = double(foam) * 4.0 / 3.0 * M_PI * 0.03 * 0.03 * 0.03;
  EXPECT_NEAR(std::stod(info.output.substr(integral + 9)), expected, 1e-4 * expected) << info.output;

  r = run_spume("simulate " + args(look + "--set diffuse.seed=9").replace(args().find("--quiet"), 7, ""));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(testing::contains(r.output, "diffuse_fog: removed 8 .vdb files of frames 1-8 (output.fog is off)"))
      << r.output;
  EXPECT_FALSE(fs::exists(out("diffuse_fog")));
}

// Houdini's age and life on every exported particle (at 25 fps and 2 substeps): the same particle is
// 1/25 s older each frame; one new since the previous frame was emitted at the start of one of the two
// steps since (0.04 or 0.02 s ago); life - age is the remaining lifetime. The BGEO files carry the
// same two float attributes.
TEST_F(Exports, AgeGrowsByOneFrameIntervalAndLifeMinusAgeIsTheRemainingLifetime) {
  ASSERT_EQ(run_spume("simulate " + args("--vdb --bgeo --set fluid.fps=25 --set diffuse.substeps=2")).status, 0);
  size_t followed = 0, born = 0;
  std::map<uint64_t, Ages> before = vdb_ages(out("diffuse_vdb/" + numbered(1, ".vdb")));
  for (int k = 2; k <= 8; ++k) {
    const std::map<uint64_t, Ages> now = vdb_ages(out("diffuse_vdb/" + numbered(k, ".vdb")));
    for (const auto& [id, a] : now) {
      EXPECT_NEAR(a.life - a.age, a.lifetime, 1e-5f * a.life) << "frame " << k << " id " << id;
      const auto earlier = before.find(id);
      if (earlier != before.end()) {
        EXPECT_NEAR(a.age - earlier->second.age, 0.04f, 1e-5f) << "frame " << k << " id " << id;
        ++followed;
      } else {
        // Emitted in one of the two steps since the previous frame: 0.04 or 0.02 s ago.
        EXPECT_TRUE(std::fabs(a.age - 0.04f) < 1e-6f || std::fabs(a.age - 0.02f) < 1e-6f)
            << "frame " << k << " id " << id << ": age " << a.age;
        ++born;
      }
    }
    const BgeoInfo info = read_bgeo_info(out("diffuse_bgeo/" + numbered(k, ".bgeo")));
    std::set<std::string> floats;
    for (const PointAttribute& a : info.point_attributes)
      if (a.type == "float") floats.insert(a.name);
    EXPECT_TRUE(floats.count("age") && floats.count("life")) << k;
    before = now;
  }
  EXPECT_GT(followed, 100u);
  EXPECT_GT(born, 100u);
  // spume info reads the ages back: at frame 8 the youngest was born one step ago (0.02 s) at the least,
  // the oldest at frame 1's first step (7/25 s) at the most.
  const CommandResult info = run_spume("info " + out("diffuse_vdb/" + numbered(8, ".vdb")).string());
  const size_t at = info.output.find("  age: ");
  ASSERT_NE(at, std::string::npos) << info.output;
  std::istringstream ages(info.output.substr(at + 7));
  double young = -1, old = -1;
  std::string dots;
  ASSERT_TRUE(ages >> young >> dots >> old) << info.output;
  EXPECT_GE(young, 0.02 - 1e-6);
  EXPECT_LE(old, 7.0 / 25.0 + 1e-6);
  EXPECT_LT(young, old);
}

TEST_F(Exports, AFarmRunsTheSimulationJobWhileTheVdbFilesAreMissing) {
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

TEST_F(Exports, SameBytesForOneAndTwoThreads) {
  ASSERT_EQ(run_spume("simulate " + args("--vdb --threads 1", "one")).status, 0);
  ASSERT_EQ(run_spume("simulate " + args("--vdb --threads 2", "two")).status, 0);
  for (int k = 1; k <= 8; ++k) {
    const std::string name = "diffuse_vdb/" + numbered(k, ".vdb");
    EXPECT_TRUE(testing::read_file(out(name, "one")) == testing::read_file(out(name, "two"))) << name;
  }
}

}  // namespace
}  // namespace spume
