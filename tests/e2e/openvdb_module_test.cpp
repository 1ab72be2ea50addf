// OpenVDB is opened only by the runs that read or write .vdb files (sim/io/vdb_module.h): the loader's
// own log (LD_DEBUG=libs) shows libopenvdb loaded for a Mantaflow frame and never for a SPlisHSPlasH
// run, and a spume copied without the module beside it still runs .bgeo caches and refuses a .vdb
// with a message that names the module and where it belongs.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/run_command.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/text.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using testing::CommandResult;
using testing::contains;
using testing::run_spume;

const fs::path kData = fs::path(SPUME_TEST_DATA_DIR);
const std::string kOpenVdbLoaded = "libopenvdb.so";  // as LD_DEBUG names it, loaded or initialised

TEST(OpenVdbModule, OnlyARunWithVdbFilesLoadsOpenVdb) {
  testing::TempDir dir;
  const CommandResult bgeo =
      run_spume("simulate --fluid '" + (kData / "splishsplash_dambreak/ParticleData_Fluid_%d.bgeo").string() +
                    "' --radius 0.025 --fps 25 --out " + (dir / "bgeo").string(),
                testing::SpumeOptions::after("export LD_DEBUG=libs"));
  ASSERT_EQ(bgeo.status, 0) << bgeo.output;
  ASSERT_TRUE(contains(bgeo.output, "calling init: ")) << "LD_DEBUG gave no loader log:\n" << bgeo.output;
  EXPECT_FALSE(contains(bgeo.output, "libopenvdb")) << bgeo.output;
  EXPECT_FALSE(contains(bgeo.output, "libspume_vdb")) << bgeo.output;

  const CommandResult vdb = run_spume("info " + (kData / "mantaflow/data/fluid_data_0002.vdb").string(),
                                      testing::SpumeOptions::after("export LD_DEBUG=libs"));
  ASSERT_EQ(vdb.status, 0) << vdb.output;
  EXPECT_TRUE(contains(vdb.output, kOpenVdbLoaded)) << vdb.output;
  EXPECT_TRUE(contains(vdb.output, "libspume_vdb.so")) << vdb.output;
}

TEST(OpenVdbModule, ACopyOfSpumeWithoutTheModuleRunsBgeoAndRefusesVdbNamingTheModule) {
  testing::TempDir dir;
  const fs::path copy = dir / "spume";
  fs::copy_file(SPUME_BINARY, copy);
  const CommandResult bgeo = testing::run_command(
      copy.string() + " info " + (kData / "splishsplash_dambreak/ParticleData_Fluid_20.bgeo").string() + " 2>&1");
  EXPECT_EQ(bgeo.status, 0) << bgeo.output;

  const CommandResult vdb =
      testing::run_command(copy.string() + " info " + (kData / "mantaflow/data/fluid_data_0002.vdb").string() + " 2>&1");
  EXPECT_EQ(vdb.status, 1) << vdb.output;
  EXPECT_TRUE(contains(vdb.output, "cannot open the OpenVDB module " + (dir / "libspume_vdb.so").string()))
      << vdb.output;
  EXPECT_TRUE(contains(vdb.output, "beside the spume executable (" + copy.string() + ")")) << vdb.output;
  EXPECT_FALSE(contains(vdb.output, "internal error")) << vdb.output;
}

}  // namespace
}  // namespace spume
