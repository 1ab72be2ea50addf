// ParamReader::effective: the values a run uses, as records compare them: a key
// written at its default equals the key left out; a changed value differs; what is written but never
// read as a value stays as written; arrays of objects keep their order.
#include <gtest/gtest.h>

#include "sim/core/params.h"

namespace spume {
namespace {

Json effective_after_reading(const char* text) {
  const ParamReader root = ParamReader::from_json(Json::parse(text), "test.json");
  const ParamReader d = root.child("diffuse");
  d.number("drag", 0.5);
  d.integer_in("seed", 1, 0, 100);
  d.choice("bubble_drag", "exponential", {"exponential", "paper"});
  d.range("tau", {5.0, 20.0});
  for (const ParamReader& s : root.array_of_objects("solids")) {
    s.text("type", "box");
    s.vec3("min", Vec3f(0, 0, 0));
    s.has("motion");  // looked at, never read as a value
  }
  return Json{{"diffuse", root.effective("diffuse")}, {"solids", root.effective("solids")}};
}

TEST(ParamEffective, AKeyWrittenAtItsDefaultEqualsTheKeyLeftOut) {
  const Json defaults = effective_after_reading(R"({})");
  const Json written = effective_after_reading(
      R"({"diffuse": {"drag": 0.5, "seed": 1, "bubble_drag": "exponential", "tau": [5, 20]}})");
  EXPECT_EQ(defaults, written);
  EXPECT_EQ(defaults["diffuse"], Json::parse(R"({"drag": 0.5, "seed": 1, "bubble_drag": "exponential",
                                                  "tau": [5.0, 20.0]})"));
  EXPECT_TRUE(defaults["solids"].is_null());  // none written, none read
  EXPECT_NE(effective_after_reading(R"({"diffuse": {"drag": 0.9}})")["diffuse"]["drag"], defaults["diffuse"]["drag"]);
}

TEST(ParamEffective, ArraysKeepTheirOrderAndWhatIsOnlyLookedAtStaysAsWritten) {
  const Json e = effective_after_reading(
      R"({"solids": [{"type": "tank"}, {"min": [1, 2, 3], "motion": {"type": "keyframes"}}]})");
  EXPECT_EQ(e["solids"], Json::parse(R"([{"type": "tank", "min": [0.0, 0.0, 0.0]},
                                         {"type": "box", "min": [1.0, 2.0, 3.0], "motion": {"type": "keyframes"}}])"));
}

}  // namespace
}  // namespace spume
