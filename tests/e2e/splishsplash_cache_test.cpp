// Frames of real SPlisHSPlasH output (tests/data/splishsplash_*): a dam break running up its far wall
// and an emitter whose particle count grows and whose storage order changes. Post-processed with the
// tank given, as a user would: what is emitted stays in the tank, and bubbles are where water is.
#include <gtest/gtest.h>

#include <filesystem>

#include "sim/core/frames.h"
#include "sim/io/particle_file.h"
#include "sim/io/spume_cache.h"
#include "tests/support/run_spume.h"
#include "tests/support/temp_dir.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

struct Cache {
  std::string folder;
  float radius;
  double fps;
  Vec3f tank_min, tank_max;
  int last_frame;
};

class SplishsplashCache : public ::testing::TestWithParam<Cache> {};

TEST_P(SplishsplashCache, WhatIsEmittedStaysInTheTankAndBubblesSitInWater) {
  const Cache& c = GetParam();
  const fs::path data = fs::path(SPUME_TEST_DATA_DIR) / c.folder;
  const testing::TempDir temp;
  const fs::path& out = temp.path;
  char tank[256];
  std::snprintf(tank, sizeof tank, "%g,%g,%g,%g,%g,%g", c.tank_min.x(), c.tank_min.y(), c.tank_min.z(),
                c.tank_max.x(), c.tank_max.y(), c.tank_max.z());
  const testing::CommandResult r =
      testing::run_spume("simulate --fluid '" + (data / "ParticleData_Fluid_%d.bgeo").string() + "' --radius " +
                         std::to_string(c.radius) + " --fps " + std::to_string(c.fps) + " --tank " + tank + " --out " +
                         out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;  // radius and domain fit the cache

  char name[64];
  std::snprintf(name, sizeof name, "ParticleData_Fluid/diffuse/diffuse_%04d.spd", c.last_frame);
  const DiffuseFrame diffuse = read_diffuse_cache(out / name);
  const FluidFrame fluid = read_fluid_file(data / ("ParticleData_Fluid_" + std::to_string(c.last_frame) + ".bgeo"));
  ASSERT_GT(diffuse.size(), 100u) << "the flow emits";
  const float reach = 4.0f * c.radius, slack = 1e-3f;
  size_t bubbles = 0, dry_bubbles = 0;
  for (size_t i = 0; i < diffuse.size(); ++i) {
    const Vec3f& p = diffuse.positions[i];
    // Inside the tank's walls (its open top allows spray above the rim).
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(p[a], c.tank_min[a] - slack) << i;
      if (a != 1) {
        EXPECT_LE(p[a], c.tank_max[a] + slack) << i;
      }
    }
    if (diffuse.types[i] != DiffuseType::Bubble) continue;
    ++bubbles;
    bool wet = false;
    for (size_t j = 0; j < fluid.size() && !wet; ++j) wet = (fluid.positions[j] - p).squaredNorm() <= reach * reach;
    dry_bubbles += !wet;
  }
  ASSERT_GT(bubbles, 10u);
  EXPECT_LE(dry_bubbles * 50, bubbles) << dry_bubbles << " of " << bubbles << " bubbles have no fluid within 4r";
}

INSTANTIATE_TEST_SUITE_P(
    RealFrames, SplishsplashCache,
    ::testing::Values(Cache{"splishsplash_dambreak", 0.021f, 25.0, {-1.55f, 0, -0.8f}, {1.55f, 8, 0.8f}, 22},
                      Cache{"splishsplash_emitter", 0.015f, 50.0, {-1.3f, -0.05f, -0.5f}, {1.3f, 2.05f, 0.5f}, 47}),
    [](const ::testing::TestParamInfo<Cache>& param) { return param.param.folder; });

}  // namespace
}  // namespace spume
