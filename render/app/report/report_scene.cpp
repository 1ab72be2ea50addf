#include "render/app/report/report_scene.h"

#include <fstream>
#include <sstream>

#include "sim/core/error.h"
#include "sim/stage/simulate_scene.h"

namespace spume::report {

SceneSetup load_report_scene(const StudyContext& c) {
  cli::ParsedArgs args;
  args.positional = {c.scene_path.string()};
  args.values["out"] = {c.out_root.string()};
  if (c.quiet) args.values["quiet"];
  const SceneSetup setup = load_scene_setup(args);
  DiffuseStageOptions options;
  options.out_root = setup.out_root;
  options.quiet = c.quiet;
  const SceneSimulation done = simulate_scene(setup.sim, options, true);
  if (!done.fluid.reused && done.fluid.frames > 0) c.progress(str("simulated the fluid of ", setup.sim.name));
  if (!done.diffuse.reused) c.progress(str("simulated the diffuse material of ", setup.sim.name));
  return setup;
}

int busiest_frame(const SceneSetup& setup) {
  const auto path = setup.out_root / setup.sim.name / "stats.csv";
  std::ifstream in(path);
  if (!in) fail(path.string(), ": missing (the diffuse stage writes it)");
  std::string line;
  std::getline(in, line);  // frame,time,fluid,spray,foam,bubbles,...
  if (line.rfind("frame,time,fluid,spray,foam,bubbles", 0) != 0) fail(path.string(), ": unexpected header \"", line, "\"");
  int best = -1;
  double most = -1;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(row, cell, ',') && v.size() < 6) v.push_back(std::stod(cell));
    if (v.size() < 6) fail(path.string(), ": short row \"", line, "\"");
    if (v[3] + v[4] + v[5] > most) most = v[3] + v[4] + v[5], best = int(v[0]);
  }
  if (best < 0 || most <= 0) fail(path.string(), ": no frame holds diffuse particles; nothing to measure");
  return best;
}

}  // namespace spume::report
