#pragma once
// A small scene that makes all three diffuse types: eight BGEO frames of two blocks of water thrown at
// each other in a tank (testing::blocks_closing_in), and the scene file "blocks" reading them.
#include <filesystem>
#include <fstream>
#include <string>

#include "sim/io/bgeo.h"
#include "tests/support/test_fluids.h"

namespace spume::testing {

// Writes DIR/cache/fluid_1..8.bgeo and DIR/scene.json; `render`, when given, is the scene's "render"
// object (JSON).
inline void write_blocks_scene(const std::filesystem::path& dir, const std::string& render = "") {
  std::filesystem::create_directories(dir / "cache");
  for (int k = 1; k <= 8; ++k)
    write_bgeo(dir / "cache" / ("fluid_" + std::to_string(k) + ".bgeo"), blocks_closing_in(k, 0.16f, 0.5f, Vec3f(2.0f, 1, 0)));
  std::ofstream(dir / "scene.json") << R"({
      "name": "blocks",
      "fluid": {"files": "cache/fluid_%d.bgeo", "radius": 0.02},
      "solids": [{"type": "tank", "min": [-0.1, -0.02, -0.1], "max": [0.6, 0.6, 0.3]}],
      "diffuse": {"k_ta": 2000, "k_wc": 2000})"
                                    << (render.empty() ? "" : ",\n      \"render\": " + render) << "\n    }";
}

}  // namespace spume::testing
