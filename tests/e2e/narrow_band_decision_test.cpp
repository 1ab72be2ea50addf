// Narrow bands (MODEL.md §9.1) through the binary: `spume info` and a run decide by the same test on
// the same cells, so they give one answer with the same numbers; an air pocket in an SPH cache is not
// filled, and the run says why, naming what it measured.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "sim/io/bgeo.h"
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

const fs::path kJet = fs::path(SPUME_TEST_DATA_DIR) / "../../../shared/data/blender_mantaflow_jet";

size_t occurrences(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// What `info` says of a file's interior: the text after "interior: ", up to what only info adds.
std::string info_verdict(const std::string& output) {
  const size_t begin = output.find("interior: ");
  if (begin == std::string::npos) return "";
  const size_t from = begin + 10;
  size_t end = output.find("; a run fills it", from);
  end = std::min(end, output.find(" (h = 4 r with r = ", from));
  return output.substr(from, end - from);
}

// The block: r = 0.02 on a 2r lattice, 1.2 x 0.8 x 0.8 m, ids, a constant count, moving at
// 0.5 m/s along x; with a spherical void of radius 0.26 m about its centre, or hollow below a band
// 0.24 m (3 h) deep under every face.
FluidFrame block(int k, bool hollow) {
  const Vec3f size(1.2f, 0.8f, 0.8f), centre = size / 2, u(0.5f, 0.0f, 0.0f);
  std::vector<Vec3f> x, v;
  for (const Vec3f& p : testing::lattice(Vec3f::Constant(0.02f), size - Vec3f::Constant(0.02f), 0.04f)) {
    const float depth = std::min({p.x(), size.x() - p.x(), p.y(), size.y() - p.y(), p.z(), size.z() - p.z()});
    if (hollow ? depth < 0.24f : (p - centre).norm() > 0.26f) x.push_back(p + u * (k / 25.0f)), v.push_back(u);
  }
  return testing::frame_of(k, k / 25.0, x, v);
}

class BlockCaches : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* name : {"pocket", "hollow"}) {
      fs::create_directories(dir / name);
      for (int k = 1; k <= 3; ++k)
        write_bgeo(dir / name / ("f_" + std::to_string(k) + ".bgeo"), block(k, std::string(name) == "hollow"));
    }
  }
  CommandResult simulate(const std::string& name, const std::string& more = "") const {
    return run_spume("simulate --fluid '" + (dir / name / "f_%d.bgeo").string() + "' --radius 0.02 --fps 25 --out " +
                     (dir / ("out_" + name)).string() + " " + more);
  }
  const testing::TempDir temp;
  const fs::path& dir = temp.path;
};

// Case 3. The void is enclosed (9.6% of the block), but the cache is not known to be FLIP: air, not
// filled, said once with what was measured.
TEST_F(BlockCaches, AnAirPocketInAnSphCacheIsNotFilledAndTheRunSaysWhy) {
  const CommandResult info = run_spume("info " + (dir / "pocket/f_1.bgeo").string());
  ASSERT_EQ(info.status, 0) << info.output;
  const std::string verdict = info_verdict(info.output);
  EXPECT_TRUE(verdict.rfind("ENCLOSED, not filled: ", 0) == 0) << info.output;
  const CommandResult r = simulate("pocket");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "note: frame 1's interior: " + verdict)) << r.output;
  EXPECT_EQ(occurrences(r.output, "'s interior: "), 1u) << r.output;  // one note, not one a frame
  EXPECT_FALSE(contains(r.output, "massless particles")) << r.output;
  EXPECT_FALSE(contains(r.output, "narrow-band cache")) << r.output;
  EXPECT_TRUE(contains(r.output, "set fluid.particles to \"flip\" to fill it")) << r.output;
  // Said to be FLIP, its enclosed interior is a band's, and filled.
  const CommandResult flip = simulate("pocket", "--set fluid.particles=flip");
  ASSERT_EQ(flip.status, 0) << flip.output;
  EXPECT_TRUE(contains(flip.output, "frame 1's interior: a NARROW BAND: ")) << flip.output;
  EXPECT_TRUE(contains(flip.output, "in a FLIP cache (fluid.particles = flip)")) << flip.output;
  EXPECT_TRUE(contains(flip.output, "massless particles")) << flip.output;
}

// A block hollow below a band 3 h deep, as a FLIP cache might keep it: from SPH files it is not filled
// either (nothing says it is FLIP); said to be FLIP, it is. info and the run say the same of it.
TEST_F(BlockCaches, AHollowBlockIsFilledWhenSaidToBeFlipAndInfoAgrees) {
  const CommandResult info = run_spume("info " + (dir / "hollow/f_1.bgeo").string());
  ASSERT_EQ(info.status, 0) << info.output;
  const std::string verdict = info_verdict(info.output);
  EXPECT_TRUE(verdict.rfind("ENCLOSED, not filled: ", 0) == 0) << info.output;
  const CommandResult r = simulate("hollow");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "note: frame 1's interior: " + verdict)) << r.output;
  const CommandResult flip = simulate("hollow", "--set fluid.particles=flip");
  ASSERT_EQ(flip.status, 0) << flip.output;
  EXPECT_TRUE(contains(flip.output, "frame 1's interior: a NARROW BAND: ")) << flip.output;
  EXPECT_TRUE(contains(flip.output, "massless particles")) << flip.output;
}

// Case 1. The shared jet's frame 30: info and a run over frames 30-31 at the radius info implies give
// the same verdict, with the same cells and counts (before, info said "full (593 enclosed cells)" on
// cells of twice the median nearest-neighbour distance while the run filled 3,885 enclosed cells of h).
// At the README's rounded --radius 0.0078 (cells of 0.0312 m, off Mantaflow's grid) it is a band too.
TEST(NarrowBandDecision, InfoAndTheRunAgreeOnTheSharedJet) {
  const fs::path frame = kJet / "data/fluid_data_0030.vdb";
  if (!fs::exists(frame)) GTEST_SKIP() << frame << " not present";
  const CommandResult info = run_spume("info " + frame.string());
  ASSERT_EQ(info.status, 0) << info.output;
  const std::string verdict = info_verdict(info.output);
  EXPECT_TRUE(verdict.rfind("a NARROW BAND: ", 0) == 0) << info.output;
  EXPECT_TRUE(contains(verdict, "cells of h = 0.03125 m")) << verdict;  // the cell is named: a quarter of Mantaflow's
  EXPECT_TRUE(contains(info.output, "h = 4 r with r = 0.0078125 m, a quarter of Mantaflow's cell")) << info.output;
  for (const std::string radius : {"0.0078125", "0.0078"}) {
    testing::TempDir dir;
    const CommandResult r = run_spume("simulate --fluid '" + (kJet / "data/fluid_data_%04d.vdb").string() + "' --radius " +
                                      radius + " --fps 24 --frames 30-31 --out " + (dir / "out").string());
    ASSERT_EQ(r.status, 0) << r.output;
    if (radius == "0.0078125") EXPECT_TRUE(contains(r.output, "frame 30's interior: " + verdict)) << verdict << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, "frame 30's interior: a NARROW BAND: ")) << radius << "\n" << r.output;
    EXPECT_TRUE(contains(r.output, "massless particles")) << radius << "\n" << r.output;
  }
}

}  // namespace
}  // namespace spume
