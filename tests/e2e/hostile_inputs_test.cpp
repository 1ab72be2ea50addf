// Nothing silently absurd, third round, through the spume binary: a small address space (threads that
// cannot start, memory that runs out), odd masses in real files, spume's own .vdb export, and files
// that are not what their names say, however large. Large files are sparse (no disk), and the binary
// runs under `ulimit -v` (RLIMIT_AS in its shell), so reading one whole fails at once instead of
// taking gigabytes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "sim/core/error.h"
#include "sim/core/frames.h"
#include "sim/io/bgeo.h"
#include "sim/io/ply.h"
#include "sim/io/vdb_points_writer.h"
#include "tests/support/files.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_fluids.h"
#include "tests/support/text.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

using testing::CommandResult;
using testing::contains;
using testing::run_spume;
using testing::SpumeOptions;

constexpr uint64_t kGiB = uint64_t(1) << 30;

// `head`, then zeros up to `size` bytes: a sparse file, which takes no disk.
fs::path sparse_file(const fs::path& path, const std::string& head, uint64_t size) {
  std::ofstream(path, std::ios::binary) << head;
  fs::resize_file(path, size);
  return path;
}

// Under an address space of about 977 MiB, which none of the files below may need, and in which
// reading any of them whole fails.
const SpumeOptions kSmallAddressSpace = SpumeOptions::after("ulimit -v 1000000");

// Case 7. Under small address spaces (ulimit -v), --version and info answer, or exit 1 saying that the
// limit leaves no room to start (or, below what the loader needs, 127 with its message): never an abort. Below about 330 MB the libraries spume
// links cannot start the threads they start while loading (log4cplus, through OpenVDB, aborted there);
// at 500 MB Mesa crashed creating the context --version asks for its version. With 1 GiB both answer.
TEST(HostileInputs, SmallAddressSpacesGiveAnAnswerOrAMessageNeverAnAbort) {
  SPUME_SKIP_UNDER_ADDRESS_SANITIZER();
  const testing::TempDir dir;
  FluidFrame two;
  two.positions = {Vec3f(0, 0, 0), Vec3f(0.04f, 0, 0)};
  write_ply(dir / "two.ply", two);
  for (const int kib : {300000, 400000, 500000, 700000, 1048576}) {
    const SpumeOptions limit = SpumeOptions::after(str("ulimit -v ", kib));
    for (const std::string& command : std::vector<std::string>{"--version", "info " + (dir / "two.ply").string()}) {
      const CommandResult r = run_spume(command, limit);
      const std::string at = str("ulimit -v ", kib, ", spume ", command, ": ");
      if (kib == 1048576) EXPECT_EQ(r.status, 0) << at << r.output;
      // Below about 310 MB the dynamic loader itself cannot map spume's libraries and exits 127 with its
      // own message ("cannot allocate TLS ...", "error while loading shared libraries: ... failed to map
      // segment", by which library comes first), before any of spume's code runs: no abort, no core.
      if (r.status == 127 && kib < 310000) {
        EXPECT_TRUE(contains(r.output, "cannot allocate") || contains(r.output, "error while loading shared libraries"))
            << at << r.output;
        continue;
      }
      ASSERT_TRUE(r.status == 0 || r.status == 1) << at << r.output;
      if (r.status == 1) {
        EXPECT_TRUE(contains(r.output, "spume: error: cannot start: a library failed while loading")) << at << r.output;
        EXPECT_TRUE(contains(r.output, "its limit (ulimit -v) of ")) << at << r.output;
      } else {
        EXPECT_TRUE(contains(r.output, command == "--version" ? "Mesa:    " : "points: 2")) << at << r.output;
      }
    }
  }
}

// Case 8. Masses of -1 (Houdini's "not set"): info shows them and says what is odd; simulate gives
// those particles the uniform mass rho0 (2r)^3 = 1000 * 0.04^3 = 0.064 kg and says so, so the run is
// the run of the same frames without masses, byte for byte.
TEST(HostileInputs, MassesOfMinusOneAreDescribedByInfoAndWeighedUniformlyBySimulate) {
  const testing::TempDir dir;
  for (const char* folder : {"with", "without"}) fs::create_directories(dir / folder);
  for (int k = 1; k <= 3; ++k) {
    FluidFrame f = testing::blocks_closing_in(k, 0.16f, 0.5f, Vec3f(2, 1, 0));
    write_ply(dir / "without" / ("fluid_" + std::to_string(k) + ".ply"), f);
    f.masses.assign(f.size(), -1.0f);
    if (k == 1) f.masses[0] = 0.064f;  // one usable mass: kept as it is
    write_ply(dir / "with" / ("fluid_" + std::to_string(k) + ".ply"), f);
  }
  const size_t n = testing::blocks_closing_in(1, 0.16f, 0.5f, Vec3f(2, 1, 0)).size();
  const CommandResult info = run_spume("info " + (dir / "with/fluid_1.ply").string());
  EXPECT_EQ(info.status, 0) << info.output;
  EXPECT_TRUE(contains(info.output, "masses: -1 .. 0.064 kg")) << info.output;
  EXPECT_TRUE(contains(info.output, "odd: " + std::to_string(n - 1) + " of " + std::to_string(n) +
                                        " masses are not > 0 (-1 kg)"))
      << info.output;

  auto simulate = [&](const char* folder) {
    return run_spume(str("simulate --fluid '", (dir / folder).string(), "/fluid_%d.ply' --radius 0.02 --out ",
                         (dir / folder / "out").string()));
  };
  const CommandResult with = simulate("with");
  ASSERT_EQ(with.status, 0) << with.output;
  EXPECT_TRUE(contains(with.output, "warning: frame 1: " + std::to_string(n - 1) + " of " + std::to_string(n) +
                                        " masses are not > 0 (-1 kg)"))
      << with.output;
  EXPECT_TRUE(contains(with.output, "the uniform mass rho0 (2r)^3 = 0.064 kg")) << with.output;
  const CommandResult without = simulate("without");
  ASSERT_EQ(without.status, 0) << without.output;
  EXPECT_FALSE(contains(without.output, "masses are not > 0")) << without.output;
  for (int k = 1; k <= 3; ++k) {
    const std::string spd = str("out/fluid/diffuse/diffuse_", std::string(4 - std::to_string(k).size(), '0'), k, ".spd");
    ASSERT_TRUE(fs::exists(dir / "with" / spd)) << spd;
    EXPECT_EQ(testing::read_file(dir / "with" / spd), testing::read_file(dir / "without" / spd)) << spd;
  }
}

// Case 9. spume's own .vdb export holds 64-bit diffuse ids (parent id << 32 | birth step << 12 | sample):
// info describes it as diffuse particles, with the counts by type and the ids as written. Read as a
// fluid, it is refused as what it is.
TEST(HostileInputs, InfoDescribesSpumesOwnVdbExportWithItsSixtyFourBitIds) {
  const testing::TempDir dir;
  DiffuseFrame d;
  d.index = 12;
  d.time = 0.5;
  const uint64_t ids[] = {(uint64_t(173) << 32) | (5 << 12) | 0, (uint64_t(173) << 32) | (5 << 12) | 1,
                          (uint64_t(4000000000u) << 32) | (7 << 12) | 3, uint64_t(9), uint64_t(10)};
  const DiffuseType types[] = {DiffuseType::Spray, DiffuseType::Foam, DiffuseType::Foam, DiffuseType::Bubble,
                               DiffuseType::Spray};
  for (size_t i = 0; i < 5; ++i) {
    d.ids.push_back(ids[i]);
    d.positions.push_back(Vec3f(0.1f * float(i), 0.2f, 0.3f));
    d.velocities.push_back(Vec3f(1.0f, -0.5f, 0.25f * float(i)));
    d.lifetimes.push_back(2.0f + float(i));
    d.types.push_back(types[i]);
  }
  const fs::path vdb = dir / "diffuse_0012.vdb";
  write_vdb_points(vdb, d, vdb_points_voxel_size(0.02f));
  const CommandResult r = run_spume("info " + vdb.string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "content: spume diffuse particles (output.vdb), frame 12, time 0.5 s")) << r.output;
  EXPECT_TRUE(contains(r.output, "particles: 5 (spray 2, foam 2, bubble 1)")) << r.output;
  EXPECT_TRUE(contains(r.output, "lifetime: 2 .. 6 s")) << r.output;
  EXPECT_TRUE(contains(r.output, str("ids: 9 .. ", ids[2], " (64-bit"))) << r.output;

  fs::copy_file(vdb, dir / "fluid_1.vdb");
  const CommandResult s = run_spume("simulate --fluid '" + (dir / "fluid_%d.vdb").string() + "' --radius 0.02 --out " +
                                    (dir / "out").string());
  EXPECT_EQ(s.status, 1) << s.output;
  EXPECT_TRUE(contains(s.output, "fluid_1.vdb: holds spume's diffuse particles")) << s.output;
  EXPECT_TRUE(contains(s.output, "not a fluid frame")) << s.output;
}

// Case 10. 2 GiB of zeros under each name: refused on its first bytes, in an address space that
// reading it whole would break.
TEST(HostileInputs, LargeFilesThatAreNotWhatTheyAreNamedAreRefusedOnTheirFirstBytes) {
  const testing::TempDir dir;
  const std::pair<const char*, const char*> cases[] = {
      {"zeros.vtk", "not a legacy VTK file: the first line must be '# vtk DataFile Version x.y'"},
      {"zeros.ply", "not a PLY file: it must start with the line 'ply'"},
      {"zeros.bgeo.sc", "not a .bgeo.sc file: it must start with 'scf1'"},
      {"zeros.vtu", "not an XML VTK file"}};
  for (const auto& [name, message] : cases) {
    const fs::path p = sparse_file(dir / name, "", 2 * kGiB);
    const CommandResult r = run_spume("info " + p.string(), kSmallAddressSpace);
    EXPECT_EQ(r.status, 1) << name << ": " << r.output;
    EXPECT_TRUE(contains(r.output, p.string() + ": " + message)) << r.output;
  }
  // Right magic, then zeros: the header is checked before the body is read.
  const std::pair<const char*, std::string> headed[] = {
      {"magic.vtk", "# vtk DataFile Version 3.0\n"},  // no title line within 256 characters
      {"magic.ply", "ply\n"},                         // a header of zeros, not text
  };
  for (const auto& [name, head] : headed) {
    const fs::path p = sparse_file(dir / name, head, 2 * kGiB);
    const CommandResult r = run_spume("info " + p.string(), kSmallAddressSpace);
    EXPECT_EQ(r.status, 1) << name << ": " << r.output;
    EXPECT_TRUE(contains(r.output, p.string() + ": not a")) << r.output;
    EXPECT_FALSE(contains(r.output, "out of memory")) << r.output;
  }
  // A .bgeo.sc keeps its index at its end: one cut short (no closing "1fcs") is refused from its two
  // ends, before the 2 GiB between them are read.
  const fs::path cut = sparse_file(dir / "cut.bgeo.sc", std::string("scf1") + std::string(8, '\0'), 2 * kGiB);
  const CommandResult r = run_spume("info " + cut.string(), kSmallAddressSpace);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, cut.string() + ": truncated or corrupt: a .bgeo.sc file ends with its index")) << r.output;
  EXPECT_FALSE(contains(r.output, "out of memory")) << r.output;
}

// Case 10. A 4 MiB .bgeo.sc whose one LZ4 chunk claims 2 GiB decompressed: LZ4 codes at most 255 bytes
// in one, so 4 MiB hold at most about 1 GiB; refused from its header, before anything is allocated.
TEST(HostileInputs, ABgeoScChunkClaimingMoreThanItsCodecCanHoldIsRefusedFromItsHeader) {
  const testing::TempDir dir;
  const std::string real = testing::read_file(fs::path(SPUME_TEST_DATA_DIR) / "houdini/retime_demoscene.10.bgeo.sc");
  ASSERT_EQ(real.substr(0, 4), "scf1");
  ASSERT_EQ(uint8_t(real[12 + 2]) >> 5, 1);  // LZ4, as every real file
  const uint32_t compressed = 4u << 20, claimed = 2147483000u;
  std::string file = real.substr(0, 12 + 16);
  auto put32 = [&](size_t at, uint32_t v) {
    for (int b = 0; b < 4; ++b) file[at + size_t(b)] = char((v >> (8 * b)) & 0xff);  // Blosc: little-endian
  };
  put32(12 + 4, claimed);      // nbytes
  put32(12 + 12, compressed);  // cbytes
  file.resize(12 + compressed, '\x01');
  // The index: one 8-byte number, then its size (8, big-endian) and "1fcs".
  file += std::string(8, '\0') + std::string(7, '\0') + '\x08' + "1fcs";
  const fs::path p = dir.write("claim.bgeo.sc", file);
  const CommandResult r = run_spume("info " + p.string(), kSmallAddressSpace);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, str("claims ", claimed, " decompressed bytes from ", compressed, " compressed (LZ4)")))
      << r.output;
}

// Case 11. Out of memory on a sound file: a binary PLY of 100 million points (1.2 GB of zeros, sparse)
// in an address space of 977 MiB. The message names the file, what was allocated and how much, and the
// limit; simulate says the same for the frame.
TEST(HostileInputs, OutOfMemoryNamesTheFileTheSizeAndTheLimit) {
  SPUME_SKIP_UNDER_ADDRESS_SANITIZER();
  const testing::TempDir dir;
  const uint64_t points = 100'000'000;
  const std::string head = str("ply\nformat binary_little_endian 1.0\nelement vertex ", points,
                               "\nproperty float x\nproperty float y\nproperty float z\nend_header\n");
  const fs::path p = sparse_file(dir / "big_1.ply", head, head.size() + points * 12);
  const CommandResult r = run_spume("info " + p.string(), kSmallAddressSpace);
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "spume info: error: out of memory reading " + p.string() + " (1.1 GiB)")) << r.output;
  EXPECT_TRUE(contains(r.output, "its limit (ulimit -v) is 977 MiB")) << r.output;
  EXPECT_FALSE(contains(r.output, "internal error")) << r.output;

  const CommandResult s =
      run_spume("simulate --fluid '" + (dir / "big_%d.ply").string() + "' --radius 0.02 --out " + (dir / "out").string(),
                kSmallAddressSpace);
  EXPECT_EQ(s.status, 1) << s.output;
  EXPECT_TRUE(contains(s.output, "frame 1: out of memory reading " + p.string() + " (1.1 GiB)")) << s.output;
}

}  // namespace
}  // namespace spume
