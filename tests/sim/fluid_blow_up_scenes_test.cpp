// The shipped solver scenes get the blow-up bounds worked out by hand from their files (fluid/blow_up.h:
// 5 x max(sqrt(2 |g| H), 2 x the fastest kinematic solid, 1 m/s)) and their first frames stay far from
// them. Whole runs were measured at most 1.98 x the reference speed (blow_up.h).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "sim/fluid/solver.h"
#include "sim/scene/sim_scene.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

SimScene shipped(const std::string& name) {
  const fs::path path = fs::path(SPUME_TEST_DATA_DIR).parent_path().parent_path() / "scenes" / (name + ".json");
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return read_sim_scene(ParamReader::from_json(parse_json_text(text.str(), path.string()), path.string()),
                        path.parent_path(), name);
}

struct Expected {
  const char* scene;
  double height;       // m, of the box around blocks and solids, from the scene file
  double solid_speed;  // m/s, the fastest kinematic solid
};

// Heights: the tanks' tops over the floor, the lighthouse's rock reaching 0.05 + 0.45 m below it.
// Solid speeds: sine pistons 2 pi A f (wave 0.2 m x 0.6 Hz, lighthouse 0.5 m x 0.6 Hz); the ship's
// fastest keyframe leg 1.63 m in 1.02 s.
const Expected kScenes[] = {
    {"dambreak", 1.0, 0.0},
    {"wave", 1.2, 2.0 * M_PI * 0.2 * 0.6},
    {"ship", 0.6, (1.95 - 0.32) / (1.42 - 0.4)},
    {"lighthouse", 1.9, 2.0 * M_PI * 0.5 * 0.6},
    {"tower", 1.2, 0.0},
};

TEST(FluidBlowUpScenes, ShippedScenesFirstFramesStayFarBelowTheBounds) {
  for (const Expected& e : kScenes) {
    SCOPED_TRACE(e.scene);
    const SimScene scene = shipped(e.scene);
    FluidSolver solver(scene.solver.params, scene.solver.blocks, scene.solids);
    const fluid::BlowUpLimits& l = solver.blow_up_limits();
    EXPECT_NEAR(l.height, e.height, 1e-5);
    EXPECT_NEAR(l.solid_speed, e.solid_speed, 1e-5);
    const double reference = std::max({std::sqrt(2.0 * 9.81 * e.height), 2.0 * e.solid_speed, 1.0});
    EXPECT_NEAR(l.max_fall_speed, 5.0 * reference, 1e-4);

    double worst = 0.0;  // the largest fall speed at any frame, over the bound
    for (int f = 1; f <= 6; ++f) {
      ASSERT_NO_THROW(solver.advance_to(f / scene.fluid.fps));
      const FluidFrame frame = solver.frame(f);
      for (size_t i = 0; i < frame.size(); ++i)
        worst = std::max(worst, fluid::fall_speed(l, frame.positions[i], frame.velocities[i]) / l.max_fall_speed);
    }
    EXPECT_LT(worst, 0.5);
    EXPECT_LT(solver.stats().max_density_error, 0.01);  // the bound is 0.10
  }
}

}  // namespace
}  // namespace spume
