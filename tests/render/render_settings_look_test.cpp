// The water look's render keys (surface_smoothing, water.refraction, water.scene_reflections): read
// with their defaults, their values, and errors naming the key out of range.
#include <gtest/gtest.h>

#include "sim/core/error.h"
#include "render/frame/render_settings.h"

namespace spume {
namespace {

RenderSettings read(const char* json) {
  return read_render_settings(ParamReader::from_json(Json::parse(json), "scene.json"), 0.01f);
}

TEST(RenderSettingsLook, Defaults) {
  const RenderSettings s = read("{}");
  EXPECT_EQ(s.surface.smoothing, 8);
  EXPECT_EQ(s.water.refraction, 1.0f);
  EXPECT_TRUE(s.water.scene_reflections);
}

TEST(RenderSettingsLook, Values) {
  const RenderSettings s =
      read(R"({"surface_smoothing": 0, "water": {"refraction": 0.25, "scene_reflections": false}})");
  EXPECT_EQ(s.surface.smoothing, 0);
  EXPECT_EQ(s.water.refraction, 0.25f);
  EXPECT_FALSE(s.water.scene_reflections);
}

TEST(RenderSettingsLook, OutOfRangeNamesTheKey) {
  auto message = [](const char* json) {
    try {
      read(json);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(R"({"surface_smoothing": 101})").find("surface_smoothing"), std::string::npos);
  EXPECT_NE(message(R"({"surface_smoothing": 2.5})").find("surface_smoothing"), std::string::npos);
  EXPECT_NE(message(R"({"water": {"refraction": 1.5}})").find("refraction"), std::string::npos);
  EXPECT_NE(message(R"({"water": {"scene_reflections": 1}})").find("scene_reflections"), std::string::npos);
}

}  // namespace
}  // namespace spume
