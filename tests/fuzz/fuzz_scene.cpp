// libFuzzer target: the simulation half of a scene file (scene/sim_scene.h) from JSON text, as the
// command loads it (render/app/scene/scene_file.cpp: JSON with comments -> ParamReader -> read_sim_scene ->
// unknown-key check). Nothing is read from disk: the scene's folder does not exist.
#include <cstdint>
#include <string>

#include "sim/core/error.h"
#include "sim/core/params.h"
#include "sim/scene/sim_scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace spume;
  try {
    Json json = parse_json_text(std::string(reinterpret_cast<const char*>(data), size), "fuzz.json");
    const ParamReader root = ParamReader::from_json(std::move(json), "fuzz.json");
    const SimScene scene = read_sim_scene(root, "/nonexistent/spume-fuzz", "fuzz");
    root.reject_unknown_keys();
    (void)scene;
  } catch (const Error&) {
  }
  return 0;
}
