// spume lookdev: one frame from the caches, rendered for every combination of some render keys, as a
// labelled contact sheet -- look-dev of spray vs foam radii without re-simulating.
#include <cstdio>

#include "render/app/cli/cli_args.h"
#include "render/app/commands.h"
#include "sim/core/error.h"
#include "sim/core/progress.h"
#include "render/image/contact_sheet.h"
#include "render/image/png_io.h"
#include "render/app/scene/scene_render.h"
#include "render/stage/render_stage.h"
#include "render/app/scene/scene_args.h"
#include "render/app/scene/scene_lock.h"

namespace spume {
namespace {

struct Variation {
  std::string key;                  // e.g. render.spray.radius
  std::vector<std::string> values;  // as typed (JSON values)
};

Variation parse_variation(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    cli::usage_fail("--vary \"", text, "\": expected KEY=V1,V2,... such as render.spray.radius=0.002,0.004");
  Variation v{text.substr(0, eq), {}};
  if (v.key.rfind("render.", 0) != 0)
    cli::usage_fail("--vary \"", text, "\": look-dev varies render.* keys only (the caches fix everything simulated); "
         "use --set and `spume run` for ", v.key);
  size_t start = eq + 1;
  while (start <= text.size()) {
    const auto comma = text.find(',', start);
    const std::string value = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (value.empty()) cli::usage_fail("--vary \"", text, "\": empty value in the list");
    v.values.push_back(value);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return v;
}

std::string join_values(const Variation& v) {
  std::string out;
  for (const std::string& value : v.values) out += (out.empty() ? "" : ",") + value;
  return out;
}

// Every combination, the first variation changing slowest; each is a list of "key=value" overrides.
std::vector<std::vector<std::string>> combinations(const std::vector<Variation>& vary) {
  std::vector<std::vector<std::string>> out = {{}};
  for (const Variation& v : vary) {
    std::vector<std::vector<std::string>> next;
    for (const auto& partial : out)
      for (const auto& value : v.values) {
        next.push_back(partial);
        next.back().push_back(v.key + "=" + value);
      }
    out = std::move(next);
  }
  return out;
}

int lookdev(const cli::ParsedArgs& args) {
  std::vector<Variation> vary;
  for (const auto& text : args.all("vary")) {
    Variation v = parse_variation(text);
    // Each tile is labelled with its key's value: a key varied twice would label tiles with two
    // contradictory values, one of them not the one drawn.
    for (const Variation& earlier : vary)
      if (earlier.key == v.key)
        cli::usage_fail("--vary: ", v.key, " is varied twice (", earlier.key, "=", join_values(earlier), " and ",
                        text, "); give each key once, with all its values: --vary ", v.key, "=", join_values(earlier),
                        ",", join_values(v));
    vary.push_back(std::move(v));
  }
  const auto combos = combinations(vary);
  if (combos.size() > 256) cli::usage_fail("--vary: ", combos.size(), " combinations; at most 256 fit a contact sheet");
  // Every option value is checked before the first scene is loaded.
  auto optional_int = [&](const char* name, int lo, int hi) -> std::optional<int> {
    if (auto text = args.value(name)) return cli::parse_int(*text, str("--", name), lo, hi);
    return std::nullopt;
  };
  const std::optional<int> asked_tile_width = optional_int("tile-width", 16, 4096);
  const std::optional<int> asked_frame = optional_int("frame", 0, 1 << 30);
  const std::optional<int> asked_columns = optional_int("columns", 1, 256);

  std::vector<ContactTile> tiles;
  std::filesystem::path output;
  int frame = -1;
  Progress progress("lookdev", combos.size(), args.has("quiet"));
  std::unique_ptr<OutputLock> lock;  // the caches must not change under the sheet
  for (size_t c = 0; c < combos.size(); ++c) {
    SceneSetup setup = load_scene_setup(args, combos[c]);
    if (!lock) lock = lock_scene_output(setup, OutputLock::Mode::Shared, "spume lookdev");
    const int full_width = setup.render.width;
    const int tile_width = asked_tile_width.value_or(std::min(full_width, 480));
    setup.render.height = std::max(1, int(std::lround(double(setup.render.height) * tile_width / full_width)));
    setup.render.width = tile_width;
    setup.render.exr = false;  // a contact sheet: no layers to take apart
    SceneRender scene = scene_render(setup.sim, setup.out_root);
    if (c == 0) print_input_warnings(scene);
    PreparedRender prepared = prepare_render(scene.scene, setup.render);
    const std::vector<int>& frames = scene.scene.frames;
    if (frame < 0) {
      frame = asked_frame.value_or(frames.front());
      if (!std::binary_search(frames.begin(), frames.end(), frame))
        fail("--frame ", frame, ": not a frame of ", setup.sim.name, " (", frames.front(), "-", frames.back(), ")");
      output = args.has("output") ? std::filesystem::path(*args.value("output"))
                                  : scene.scene.scene_out / "lookdev" / str("lookdev_", frame, ".png");
    }
    check_diffuse_caches(setup.sim, scene, prepared.settings, {frame});
    const LoadedFrame loaded = load_frame(prepared, frame);
    FrameRenderer renderer(prepared.settings);
    tiles.push_back({renderer.render(loaded.inputs()), combos[c]});
    if (tiles.back().labels.empty()) tiles.back().labels.push_back(str(setup.sim.name, " frame ", frame));
    progress.update(c + 1);
  }
  const int columns = asked_columns.value_or(vary.empty() ? 1 : int(vary.back().values.size()));
  write_png(output, make_contact_sheet(tiles, columns));
  progress.finish();
  if (!args.has("quiet")) std::printf("Saved: %s\n", output.string().c_str());
  return 0;
}

}  // namespace

Command cmd_lookdev() {
  cli::CommandSpec spec;
  spec.name = "lookdev";
  spec.forms = scene_command_forms("[--vary KEY=A,B,..]");
  spec.summary = "one frame for every combination of render keys, as a labelled contact sheet";
  spec.options = scene_command_options();
  spec.options.push_back({"frame", "N", "the frame to render (default: the scene's first)"});
  spec.options.push_back(
      {"vary", "KEY=A,B,..", "render key and its values, e.g. render.foam.radius=0.004,0.008", true});
  spec.options.push_back({"columns", "N", "tiles per row (default: the last --vary's count)"});
  spec.options.push_back({"tile-width", "W", "tile width in pixels (default: the scene's, at most 480)"});
  spec.options.push_back({"output", "FILE", "the sheet (default OUT/<scene>/lookdev/lookdev_<frame>.png)"});
  return {spec, lookdev};
}

}  // namespace spume
