// Nothing silently absurd, second round, through the spume binary: a radius that leaves
// every particle alone stops the run; frame names say PNG; a gzip of zeros fails on its first bytes
// with bounded memory; folders that cannot be written are named; keys written at their defaults are
// no change; a key varied twice, a --markdown prefix and a directory given to info are answered.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"
#include "tests/support/test_fluids.h"
#include "sim/io/bgeo.h"
#include "sim/io/io_bytes.h"
#include "tests/support/text.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

using testing::CommandResult;
using testing::run_spume;

using spume::testing::contains;

// Four BGEO frames (numbered 1-4) of two blocks of water on a 0.04 m lattice (radius 0.02 m) thrown at
// each other in a tank, and a scene that draws them at 64x36.
class Messages : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir / "cache");
    for (int k = 1; k <= 4; ++k)
      write_bgeo(dir / "cache" / ("fluid_" + std::to_string(k) + ".bgeo"),
                 testing::blocks_closing_in(k, 0.16f, 0.5f, Vec3f(2, 1, 0)));
    std::ofstream(dir / "scene.json") << R"({
      "name": "blocks",
      "fluid": {"files": "cache/fluid_%d.bgeo", "radius": 0.02},
      "solids": [{"type": "tank", "min": [-0.1, -0.02, -0.1], "max": [0.6, 0.6, 0.3]}],
      "diffuse": {"k_ta": 2000, "k_wc": 2000},
      "render": {"resolution": [64, 36], "camera": {"position": [0.25, 0.5, 1.2], "target": [0.25, 0.1, 0.1]}}
    })";
  }

  std::string args(const std::string& more = "") const {
    return (dir / "scene.json").string() + " --out " + (dir / "out").string() + " " + more;
  }
  fs::path out(const std::string& relative) const { return dir / "out/blocks" / relative; }

  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

// Case 2. A radius 1000 times too small (mm taken for m): the particles' spacing, 0.04 m, is far beyond
// the support radius h = 4 r = 8e-05 m, so no particle has a neighbour and every frame would be empty.
// simulate and render both stop and give the radius the spacing implies (0.04 / 2 = 0.02 m).
TEST_F(Messages, ARadiusThatLeavesEveryParticleAloneStopsSimulateAndRender) {
  for (const char* command : {"simulate ", "render "}) {
    const CommandResult r = run_spume(command + args("--set fluid.radius=2e-05"));
    EXPECT_EQ(r.status, 1) << command << r.output;
    EXPECT_TRUE(contains(r.output, "fluid.radius 2e-05 m (--radius): the fluid's particles lie 0.04 m")) << r.output;
    EXPECT_TRUE(contains(r.output, "no particle would have a neighbour")) << r.output;
    EXPECT_TRUE(contains(r.output, "Set fluid.radius (--radius) to about 0.02 m")) << r.output;
  }
  EXPECT_FALSE(fs::exists(out("diffuse/record.json")));
  EXPECT_FALSE(fs::exists(out("frames")));
  // A radius 0.035 m (spacing 0.07 m, 1.75 times the particles'): the frames are not empty, but the
  // render says the radius is doubtful as the simulation did.
  ASSERT_EQ(run_spume("simulate " + args("--set fluid.radius=0.035")).status, 0);
  const CommandResult r = run_spume("render " + args("--set fluid.radius=0.035"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "warning: fluid.radius 0.035 m implies a particle spacing of 0.07 m")) << r.output;
}

// Case 4. Frames are PNG: a .jpg name is refused naming the key, the value and what is allowed.
TEST_F(Messages, FrameNamesMustSayPng) {
  const CommandResult r = run_spume("render " + args("--set render.frames=x/%04d.jpg"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "/render/frames: \"x/%04d.jpg\" ends in \".jpg\"")) << r.output;
  EXPECT_TRUE(contains(r.output, "must end in .png")) << r.output;
  EXPECT_FALSE(fs::exists(out("x")));
}

// Case 9. A key written at its default value is the run's value: diffuse.drag 0.5 is the declared
// default (sim/keys/diffuse_keys.h; sim/keys/KEYS.md), so caches made without it are current for it; a
// real change is named by both values.
TEST_F(Messages, AKeyWrittenAtItsDefaultIsNoChange) {
  ASSERT_EQ(run_spume("simulate " + args()).status, 0);
  CommandResult r = run_spume("render " + args("--set diffuse.drag=0.5 --set gravity=[0,-9.81,0]"));
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "4 frames written")) << r.output;
  r = run_spume("render " + args("--set diffuse.drag=0.9"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "key diffuse.drag: 0.5 -> 0.9")) << r.output;
}

// Case 8. An output folder that cannot be created (under a regular file: refused to root as well) is
// named with the system's reason, not as a lock file.
TEST_F(Messages, AnOutputFolderThatCannotBeCreatedIsNamed) {
  std::ofstream(dir / "plain_file") << "a file\n";
  const fs::path root = dir / "plain_file" / "out";
  const CommandResult r = run_spume("simulate " + (dir / "scene.json").string() + " --out " + root.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, (root / "blocks").string() + ": cannot create the output folder (Not a directory)"))
      << r.output;
  EXPECT_FALSE(contains(r.output, "lock file")) << r.output;
}

// Case 10. A key varied twice would label tiles with two contradictory values: a usage error.
TEST_F(Messages, AKeyVariedTwiceIsAUsageError) {
  const CommandResult r =
      run_spume("lookdev " + args("--vary render.alpha=10,20 --vary render.alpha=30,40"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_TRUE(contains(r.output, "render.alpha is varied twice")) << r.output;
  EXPECT_TRUE(contains(r.output, "--vary render.alpha=10,20,30,40")) << r.output;
}

// Case 12. keys --markdown PREFIX prints the keys under PREFIX only: a whole group with its KEYS.md
// markers, part of one without them.
TEST_F(Messages, KeysMarkdownHonoursThePrefix) {
  CommandResult r = run_spume("keys --markdown render.water");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "| `render.water.roughness` |")) << r.output;
  EXPECT_FALSE(contains(r.output, "`render.alpha`")) << r.output;
  EXPECT_FALSE(contains(r.output, "`diffuse.")) << r.output;
  EXPECT_FALSE(contains(r.output, "<!-- keys:")) << r.output;
  r = run_spume("keys --markdown diffuse");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "<!-- keys: diffuse -->")) << r.output;
  EXPECT_TRUE(contains(r.output, "| `diffuse.drag` |")) << r.output;
  EXPECT_FALSE(contains(r.output, "`render.")) << r.output;
  EXPECT_FALSE(contains(r.output, "<!-- keys: render")) << r.output;
  r = run_spume("keys --markdown nosuchkey");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "no key starts with \"nosuchkey\"")) << r.output;
}

// Case 13. info on a directory says so and lists the particle files in it, as sequences.
TEST_F(Messages, InfoOnADirectorySaysSoAndListsItsParticleFiles) {
  std::ofstream(dir / "cache" / "notes.txt") << "not a particle file\n";
  const CommandResult r = run_spume("info " + (dir / "cache").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, (dir / "cache").string() + ": is a directory, not a particle file")) << r.output;
  EXPECT_TRUE(contains(r.output, "fluid_#.bgeo: 4 files, numbers 1 to 4")) << r.output;
  EXPECT_FALSE(contains(r.output, "notes")) << r.output;
  EXPECT_FALSE(contains(r.output, "extension")) << r.output;
}

// Case 6. `members` gzip members of 64 MiB of zeros each (written once, repeated: a 5 GiB stream from a
// file of about 23 MB), after `head` (its own member when not empty).
void write_gzip_of_zeros(const fs::path& path, const std::string& head, int members) {
  const std::string zeros(size_t(64) << 20, '\0');
  const std::string member = io::gzip_compress(zeros);
  std::ofstream out(path, std::ios::binary);
  if (!head.empty()) {
    const std::string first = io::gzip_compress(head);
    out.write(first.data(), std::streamsize(first.size()));
  }
  for (int k = 0; k < members; ++k) out.write(member.data(), std::streamsize(member.size()));
}

// What a bounded read may reach: 300 MiB, and under AddressSanitizer its quarantine too (freed memory
// it keeps, 256 MiB by default), since the ulimit is left out there (tests/support/run_spume.h).
constexpr double kPeakBoundMib = kAddressSanitizer ? 300.0 + 256.0 : 300.0;

// The largest resident set of the children waited for so far, in MiB (Linux: ru_maxrss in KiB).
double children_peak_mib() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return double(usage.ru_maxrss) / 1024.0;
}

// Case 6. 5 GiB of zeros gzipped as .bgeo.gz fails on its first five bytes, with no more memory than a
// small file costs, under an address-space limit of 1.5 GiB that inflating it whole would break.
TEST_F(Messages, AGzipOfZerosFailsOnItsMagicWithBoundedMemory) {
  const fs::path zeros = dir / "zeros.bgeo.gz";
  write_gzip_of_zeros(zeros, "", 80);
  ASSERT_LT(fs::file_size(zeros), uint64_t(64) << 20);  // level-1 deflate of zeros: about 230:1
  const CommandResult r = run_spume("info " + zeros.string(), testing::SpumeOptions::after("ulimit -v 1572864"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "not a BGEO file: first bytes are 0 0 0 0 0")) << r.output;
  EXPECT_LT(children_peak_mib(), kPeakBoundMib);

  // A valid two-point file followed by 5 GiB of zeros: read as far as its header says (and one byte
  // more, to see it does not end there), then refused as corrupt.
  FluidFrame two;
  two.positions = {Vec3f(0, 0, 0), Vec3f(0.04f, 0, 0)};
  const fs::path valid = dir / "two.bgeo.gz";
  write_bgeo(valid, two);
  const std::string plain = io::gunzip(io::read_file_bytes(valid), valid.string());
  const fs::path padded = dir / "padded.bgeo.gz";
  write_gzip_of_zeros(padded, plain, 80);
  const CommandResult p = run_spume("info " + padded.string(), testing::SpumeOptions::after("ulimit -v 1572864"));
  EXPECT_EQ(p.status, 1) << p.output;
  EXPECT_TRUE(contains(p.output, "unexpected bytes after the end marker at offset " + std::to_string(plain.size())))
      << p.output;
  EXPECT_LT(children_peak_mib(), kPeakBoundMib);
  // The same two points without the zeros read as before.
  const CommandResult ok = run_spume("info " + valid.string());
  EXPECT_EQ(ok.status, 0) << ok.output;
  EXPECT_TRUE(contains(ok.output, "points: 2")) << ok.output;
}

}  // namespace
}  // namespace spume
