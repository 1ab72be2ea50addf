// A solver scene too big for the machine is refused before anything is allocated, within a second,
// with the particle counts, the estimate and the available memory (fluid/memory_estimate.h). The
// counts behind the estimate are worked out by hand and agree with what the solver then makes.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "sim/core/error.h"
#include "sim/fluid/boundary.h"
#include "sim/fluid/memory_estimate.h"
#include "sim/fluid/solver.h"
#include "tests/stability/stability_support.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;
using stability::error_of;

Solid tank(const Vec3f& hi, bool open_top = true) {
  Solid t;
  t.kind = Solid::Kind::Tank;
  t.max = hi;
  t.open_top = open_top;
  return t;
}

Solid box(const Vec3f& lo, const Vec3f& hi) {
  Solid b;
  b.kind = Solid::Kind::Box;
  b.min = lo, b.max = hi;
  return b;
}

// r = 0.025 m: spacing 0.05 m, h = 0.1 m, so 2 layers (centres 0.025 and 0.075 m inside h).
TEST(StabilityFluidMemory, BoundaryCountsAreWorkedOutWithoutSampling) {
  struct Case {
    const char* what;
    Solid solid;
    double expected;
  };
  Solid ball;
  ball.kind = Solid::Kind::Sphere;
  ball.center = Vec3f(1, 1, 1);
  ball.radius = 0.1f;
  Solid turned = box(Vec3f(0, 0, 0), Vec3f(0.4f, 0.4f, 0.4f));
  turned.orientation = Quatf(Eigen::AngleAxisf(0.7f, Vec3f::UnitY()));
  const Case cases[] = {
      // 8 x 12 x 8 cells padded by 2 (not above the open top): 12 x 14 x 12 - 8 x 12 x 8.
      {"open tank", tank(Vec3f(0.4f, 0.6f, 0.4f)), 12.0 * 14 * 12 - 8 * 12 * 8},
      {"closed tank", tank(Vec3f(0.4f, 0.6f, 0.4f), false), 12.0 * 16 * 12 - 8 * 12 * 8},
      // 8^3 cells less the 4^3 core.
      {"box", box(Vec3f(0, 0, 0), Vec3f(0.4f, 0.4f, 0.4f)), 512.0 - 64},
      {"rotated box", turned, 512.0 - 64},
      // Thinner than 2 layers along x: all 4 x 2 x 6 cells.
      {"thin box", box(Vec3f(0, 0, 0), Vec3f(0.2f, 0.1f, 0.3f)), 48.0},
      // Shells at mid radii 0.075 and 0.025 m: round(4 pi r^2 / 0.05^2) = round(28.27) + round(3.14).
      {"sphere", ball, 28.0 + 3.0},
  };
  for (const Case& c : cases) {
    const SolidSet set({c.solid});
    EXPECT_EQ(fluid::count_boundary(set, 0.05f, 0.1f), c.expected) << c.what;
    EXPECT_EQ(double(fluid::sample_boundary(set, 0.05f, 0.1f).size()), c.expected) << c.what;
  }
}

TEST(StabilityFluidMemory, EstimateCountsWhatTheSolverMakes) {
  FluidSolverParams p;
  p.particle_radius = 0.025f;
  const std::vector<FluidBlock> blocks = {{Vec3f(0, 0, 0), Vec3f(0.2f, 0.2f, 0.2f)},     // 4^3
                                          {Vec3f(0.2f, 0, 0), Vec3f(0.4f, 0.1f, 0.4f)}};  // 4 x 2 x 8
  const SolidSet solids({tank(Vec3f(0.4f, 0.6f, 0.4f)), box(Vec3f(0.25f, 0, 0.25f), Vec3f(0.35f, 0.1f, 0.35f))});
  const fluid::MemoryEstimate e = fluid::estimate_memory(p, blocks, solids);
  EXPECT_EQ(e.fluid_particles, 64.0 + 64.0);
  EXPECT_EQ(e.boundary_particles, 1248.0 + 2 * 2 * 2);  // the small box is all shell
  EXPECT_EQ(e.bytes, 128 * fluid::kBytesPerFluidParticle + 1256 * fluid::kBytesPerBoundaryParticle);
  FluidSolver solver(p, blocks, solids);
  EXPECT_EQ(double(solver.size() + solver.stats().removed_at_start), e.fluid_particles);
  EXPECT_EQ(solver.stats().removed_at_start, 8u);  // the 2 x 2 x 2 lattice points inside the small box
  EXPECT_EQ(double(solver.stats().boundary_particles), e.boundary_particles);
}

TEST(StabilityFluidMemory, RefusalNamesTheCountsTheEstimateAndTheAvailableMemory) {
  fluid::MemoryEstimate e;
  e.fluid_particles = 4.0e6, e.boundary_particles = 1.0e6;
  e.bytes = 4.0e6 * fluid::kBytesPerFluidParticle + 1.0e6 * fluid::kBytesPerBoundaryParticle;  // 9.28 GB
  EXPECT_NO_THROW(fluid::check_memory(e, 9.3e9));
  EXPECT_NO_THROW(fluid::check_memory(e, std::nullopt));  // unknown: not refused
  const std::string message = error_of([&] { fluid::check_memory(e, 8.0e9); });
  for (const char* part : {"about 9.3 GB", "4000000 fluid particles", "1000000 boundary particles", "only 8 GB",
                           "fluid.radius"})
    EXPECT_NE(message.find(part), std::string::npos) << part << " not in: " << message;
  const std::optional<double> available = available_memory_bytes();
  ASSERT_TRUE(available.has_value());  // Linux: /proc/meminfo
  EXPECT_GT(*available, 1.0e6);
}

// 1e12 particles (a 100 m cube at r = 5 mm): more than any machine has, refused from the estimate, before
// anything is allocated (allocating first would end in std::bad_alloc, which error_of does not take).
TEST(StabilityFluidMemory, AnAbsurdBlockIsRefusedBeforeAnythingIsAllocated) {
  FluidSolverParams p;
  p.particle_radius = 0.005f;
  const std::string message = error_of([&] {
    FluidSolver solver(p, {{Vec3f(0, 0, 0), Vec3f(100, 100, 100)}}, SolidSet({tank(Vec3f(100, 120, 100))}));
  });
  EXPECT_NE(message.find("1e+12 fluid particles"), std::string::npos) << message;
  EXPECT_NE(message.find("is available"), std::string::npos) << message;
}

// A user's case, 1.25e8 particles (a 10 m cube at r = 1 cm, estimated 288 GB), through the binary, under
// a 4 GiB address-space limit: refused from the estimate, not by running out of memory part way.
TEST(StabilityFluidMemory, ATenMetreCubeAtOneCentimetreIsRefusedBeforeAllocatingWhereItCannotFit) {
  FluidSolverParams p;
  p.particle_radius = 0.01f;
  const std::vector<FluidBlock> blocks = {{Vec3f(0, 0, 0), Vec3f(10, 10, 10)}};
  const fluid::MemoryEstimate e = fluid::estimate_memory(p, blocks, SolidSet());
  EXPECT_EQ(e.fluid_particles, 500.0 * 500 * 500);
  if (e.bytes <= *available_memory_bytes()) GTEST_SKIP() << "this machine could hold it";
  const testing::TempDir temp;
  const std::filesystem::path& dir = temp.path;
  std::ofstream(dir / "big.json") << R"({"name": "big", "fluid": {"source": "solver", "radius": 0.01,
    "blocks": [{"min": [0, 0, 0], "max": [10, 10, 10]}]}})";
  const testing::CommandResult r =
      testing::run_spume("simulate " + (dir / "big.json").string() + " --out " + (dir / "out").string(),
                         testing::SpumeOptions::after("ulimit -v 4194304"));
  EXPECT_EQ(r.status, 1) << r.output;
  for (const char* part : {"125000000 fluid particles", "GB of memory", "is available"})
    EXPECT_NE(r.output.find(part), std::string::npos) << part << " not in: " << r.output;
  EXPECT_FALSE(fs::exists(dir / "out/big/fluid"));
}

}  // namespace
}  // namespace spume
