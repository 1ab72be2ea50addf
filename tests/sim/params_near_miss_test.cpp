// A required key that is missing points at an unknown key of the same object a typo away
// (ParamReader::fail_at), and never at a key spume reads.
#include <gtest/gtest.h>

#include <functional>

#include "sim/core/error.h"
#include "sim/core/params.h"

namespace spume {
namespace {

// The message of fn's Error: the reader's failure for a missing key.
std::string message_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an Error";
  return "";
}

std::string missing(const Json& scene, const std::string& object, const std::string& key) {
  const ParamReader root = ParamReader::from_json(scene, "s.json");
  return message_of([&] {
    const ParamReader r = root.child(object);
    if (!r.has(key)) r.fail_at(key, "missing");
  });
}

TEST(ParamsNearMiss, MissingKeyNamesTheTypoBesideIt) {
  EXPECT_EQ(missing(Json::parse(R"({"fluid": {"radus": 0.02, "fps": 50}})"), "fluid", "radius"),
            "s.json: /fluid/radius: missing (did you mean \"radus\"? it is not a known key)");
  // Two edits in a six-letter key still count; the closest wins.
  EXPECT_EQ(missing(Json::parse(R"({"fluid": {"rdus": 1, "radiux": 2}})"), "fluid", "radius"),
            "s.json: /fluid/radius: missing (did you mean \"radiux\"? it is not a known key)");
}

TEST(ParamsNearMiss, NoHintForFarKeysShortKeysOrKeysSpumeReads) {
  EXPECT_EQ(missing(Json::parse(R"({"fluid": {"fps": 50}})"), "fluid", "radius"), "s.json: /fluid/radius: missing");
  // "max" is two edits from "min": too far for a three-letter key.
  EXPECT_EQ(missing(Json::parse(R"({"block": {"max": [1, 1, 1]}})"), "block", "min"), "s.json: /block/min: missing");
  // A key already read here, or read elsewhere in the scene, is known, not a typo.
  const ParamReader root = ParamReader::from_json(Json::parse(R"({"a": {"radii": 1}, "fluid": {"radii": 2}})"), "s.json");
  root.child("a").has("radii");
  EXPECT_EQ(message_of([&] { root.child("fluid").fail_at("radius", "missing"); }), "s.json: /fluid/radius: missing");
  // A present key's own failure gets no hint.
  const ParamReader present = ParamReader::from_json(Json::parse(R"({"fluid": {"radius": -1, "radus": 2}})"), "s.json");
  EXPECT_EQ(message_of([&] { present.child("fluid").fail_at("radius", "must be > 0"); }),
            "s.json: /fluid/radius: must be > 0");
}

}  // namespace
}  // namespace spume
