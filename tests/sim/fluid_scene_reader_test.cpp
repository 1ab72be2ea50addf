// Scene keys of the fluid solver and the solids: values, defaults, and errors that name the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "sim/core/error.h"
#include "sim/scene/fluid_scene_reader.h"
#include "sim/scene/solids_reader.h"
#include "tests/support/error_of.h"

namespace spume {
namespace {

using testing::error_of;

TEST(FluidSceneReader, ReadsSolverKeysAndFallsBackToDefaults) {
  const ParamReader root = ParamReader::from_json(Json::parse(R"({
    "fluid": {"source": "solver", "radius": 0.02,
              "blocks": [{"min": [0, 0, 0], "max": [1, 2, 1]}, {"min": [2, 0, 0], "max": [3, 1, 1]}],
              "solver": {"viscosity": 0.002, "cfl": 0.3, "max_dt": 0.004, "warm_start": true}}
  })"), "scene.json");
  const FluidSolverSetup s = read_fluid_solver(root.child("fluid"), Vec3f(0, 0, -9.81f));
  const FluidSolverParams defaults;
  EXPECT_FLOAT_EQ(s.params.particle_radius, 0.02f);
  EXPECT_FLOAT_EQ(s.params.viscosity, 0.002f);
  EXPECT_FLOAT_EQ(s.params.cfl, 0.3f);
  EXPECT_DOUBLE_EQ(s.params.max_dt, 0.004);
  EXPECT_TRUE(s.params.warm_start);
  EXPECT_EQ(s.params.gravity, Vec3f(0, 0, -9.81f));
  EXPECT_FLOAT_EQ(s.params.density_tolerance, defaults.density_tolerance);
  EXPECT_FLOAT_EQ(s.params.boundary_viscosity, defaults.boundary_viscosity);
  ASSERT_EQ(s.blocks.size(), 2u);
  EXPECT_EQ(s.blocks[1].min, Vec3f(2, 0, 0));
}

TEST(FluidSceneReader, ErrorsNameFileAndKey) {
  auto read = [](const char* text) {
    const ParamReader root = ParamReader::from_json(Json::parse(text), "wave.json");
    read_fluid_solver(root.child("fluid"), Vec3f(0, -9.81f, 0));
  };
  EXPECT_NE(error_of([&] { read(R"({"fluid": {"blocks": [{"min": [0,0,0], "max": [1,1,1]}]}})"); })
                .find("wave.json: /fluid/radius"),
            std::string::npos);
  EXPECT_NE(error_of([&] { read(R"({"fluid": {"radius": 0.01}})"); }).find("/fluid/blocks"), std::string::npos);
  EXPECT_NE(error_of([&] { read(R"({"fluid": {"radius": 0.01, "blocks": [{"min": [0,0,0], "max": [1,0,1]}]}})"); })
                .find("/fluid/blocks/0/max"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read(R"({"fluid": {"radius": 0.01, "blocks": [{"min": [0,0,0], "max": [1,1,1]}],
                                 "solver": {"cfl": 7}}})");
            }).find("/fluid/solver/cfl"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read(R"({"fluid": {"radius": 0.01, "support_radius": 0.03,
                                 "blocks": [{"min": [0,0,0], "max": [1,1,1]}]}})");
            }).find("/fluid/support_radius"),
            std::string::npos);
  // A typo is caught by the unknown-key check once every reader has run.
  const ParamReader root = ParamReader::from_json(
      Json::parse(R"({"fluid": {"radius": 0.01, "blocks": [{"min": [0,0,0], "max": [1,1,1]}],
                                "solver": {"viscosty": 0.1}}})"),
      "wave.json");
  read_fluid_solver(root.child("fluid"), Vec3f(0, -9.81f, 0));
  EXPECT_NE(error_of([&] { root.reject_unknown_keys(); }).find("viscosty"), std::string::npos);
}

TEST(SolidsReader, ReadsShapesAndMotions) {
  const ParamReader root = ParamReader::from_json(Json::parse(R"({"solids": [
    {"type": "tank", "min": [0, 0, 0], "max": [4, 3, 1], "open_top": false},
    {"type": "sphere", "center": [1, 1, 0.5], "radius": 0.2},
    {"type": "box", "min": [0, 0, 0], "max": [0.1, 1, 1],
     "motion": {"type": "sine", "axis": [2, 0, 0], "amplitude": 0.05, "frequency": 0.5}},
    {"type": "box", "min": [2, 0, 0], "max": [2.2, 0.5, 1],
     "motion": {"type": "keyframes", "keys": [{"time": 0, "offset": [0, 0, 0]}, {"time": 2, "offset": [1, 0, 0]}]}}
  ]})"), "ship.json");
  const SolidSet set = read_solids(root, Vec3f(0, -9.81f, 0));
  ASSERT_EQ(set.solids().size(), 4u);
  const auto& s = set.solids();
  EXPECT_EQ(s[0].kind, Solid::Kind::Tank);
  EXPECT_FALSE(s[0].open_top);
  EXPECT_EQ(s[0].up_axis, 1);
  EXPECT_EQ(s[1].kind, Solid::Kind::Sphere);
  EXPECT_FLOAT_EQ(s[1].radius, 0.2f);
  EXPECT_EQ(s[2].motion.kind, Motion::Kind::Sine);
  EXPECT_EQ(s[2].motion.axis, Vec3f(1, 0, 0));  // normalised
  EXPECT_NEAR(s[2].motion.offset(0.5).x(), 0.05f, 1e-6f);  // sin(2 pi 0.5 0.5) = 1
  EXPECT_TRUE(s[3].motion.offset(1.0).isApprox(Vec3f(0.5f, 0, 0)));
  EXPECT_NO_THROW(root.reject_unknown_keys());

  const ParamReader z_up = ParamReader::from_json(
      Json::parse(R"({"solids": [{"type": "tank", "min": [0,0,0], "max": [1,1,1]}]})"), "z.json");
  EXPECT_EQ(read_solids(z_up, Vec3f(0, 0, -9.81f)).solids()[0].up_axis, 2);
}

TEST(SolidsReader, ErrorsNameTheKey) {
  auto read = [](const char* text) {
    read_solids(ParamReader::from_json(Json::parse(text), "s.json"), Vec3f(0, -9.81f, 0));
  };
  EXPECT_NE(error_of([&] { read(R"({"solids": [{"type": "cone"}]})"); }).find("/solids/0/type"), std::string::npos);
  EXPECT_NE(error_of([&] { read(R"({"solids": [{"type": "sphere", "center": [0,0,0]}]})"); })
                .find("/solids/0/radius"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read(R"({"solids": [{"type": "box", "min": [0,0,0], "max": [1,1,1],
                       "motion": {"type": "keyframes", "keys": [{"time": 1, "offset": [0,0,0]},
                                                                {"time": 1, "offset": [1,0,0]}]}}]})");
            }).find("/solids/0/motion/keys/1/time"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              read(R"({"solids": [{"type": "box", "min": [0,0,0], "max": [1,1,1],
                       "motion": {"type": "sine", "axis": [0,0,0]}}]})");
            }).find("/solids/0/motion/axis"),
            std::string::npos);
}

TEST(SolidsReader, ReadsDynamicBodiesAndRotations) {
  const ParamReader root = ParamReader::from_json(Json::parse(R"({"solids": [
    {"type": "box", "min": [0, 0, 0], "max": [0.2, 0.1, 0.2], "rotation": {"axis": [0, 0, 2], "angle": 0.5},
     "dynamic": {"density": 500}},
    {"type": "sphere", "center": [1, 1, 1], "radius": 0.1, "dynamic": {"mass": 2.5, "friction": 0.2}},
    {"type": "box", "min": [0, 0, 0], "max": [1, 1, 1]}
  ]})"), "s.json");
  const SolidSet set = read_solids(root, Vec3f(0, -9.81f, 0));
  const Dynamics defaults;
  ASSERT_EQ(set.solids().size(), 3u);
  const Solid& box = set.solids()[0];
  EXPECT_TRUE(box.dynamics.enabled);
  EXPECT_FLOAT_EQ(box.dynamics.density, 500.0f);
  EXPECT_FLOAT_EQ(box.dynamics.mass, 0.0f);
  EXPECT_FLOAT_EQ(box.dynamics.friction, defaults.friction);
  // Rotation by 0.5 rad about z: the quaternion (cos 0.25, 0, 0, sin 0.25).
  EXPECT_NEAR(box.orientation.w(), std::cos(0.25f), 1e-6f);
  EXPECT_NEAR(box.orientation.z(), std::sin(0.25f), 1e-6f);
  EXPECT_FLOAT_EQ(set.solids()[1].dynamics.mass, 2.5f);
  EXPECT_FLOAT_EQ(set.solids()[1].dynamics.friction, 0.2f);
  EXPECT_FALSE(set.solids()[2].dynamics.enabled);
  EXPECT_FALSE(set.solids()[2].rotated());
  EXPECT_TRUE(set.any_dynamic());
}

TEST(SolidsReader, DynamicErrorsNameTheKey) {
  auto error = [](const char* text) {
    return error_of([&] { read_solids(ParamReader::from_json(Json::parse(text), "s.json"), Vec3f(0, -9.81f, 0)); });
  };
  EXPECT_NE(error(R"({"solids": [{"type": "box", "min": [0,0,0], "max": [1,1,1], "dynamic": {}}]})")
                .find("/solids/0/dynamic/density"),
            std::string::npos);
  EXPECT_NE(error(R"({"solids": [{"type": "box", "min": [0,0,0], "max": [1,1,1],
                                  "dynamic": {"density": 1, "mass": 2}}]})")
                .find("/solids/0/dynamic/density"),
            std::string::npos);
  EXPECT_NE(error(R"({"solids": [{"type": "box", "min": [0,0,0], "max": [1,1,1], "dynamic": {"mass": -1}}]})")
                .find("/solids/0/dynamic/mass"),
            std::string::npos);
  EXPECT_NE(error(R"({"solids": [{"type": "tank", "min": [0,0,0], "max": [1,1,1], "dynamic": {"mass": 1}}]})")
                .find("/solids/0/dynamic"),
            std::string::npos);
  EXPECT_NE(error(R"({"solids": [{"type": "box", "min": [0,0,0], "max": [1,1,1], "dynamic": {"mass": 1},
                                  "motion": {"type": "sine", "axis": [1,0,0]}}]})")
                .find("/solids/0/dynamic"),
            std::string::npos);
  EXPECT_NE(error(R"({"solids": [{"type": "sphere", "center": [0,0,0], "radius": 1,
                                  "rotation": {"axis": [1,0,0], "angle": 1}}]})")
                .find("/solids/0/rotation"),
            std::string::npos);
  EXPECT_NE(error(R"({"solids": [{"type": "box", "min": [0,0,0], "max": [1,1,1],
                                  "rotation": {"axis": [0,0,0], "angle": 1}}]})")
                .find("/solids/0/rotation/axis"),
            std::string::npos);
}

}  // namespace
}  // namespace spume
