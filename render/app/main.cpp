// spume: spray, foam and bubbles for particle fluids (Ihmsen et al. 2012), simulated and rendered.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "commands.h"
#include "core/error.h"

namespace {

constexpr const char* kUsage =
    "usage: spume COMMAND [options]\n"
    "commands:\n"
    "  run SCENE         simulate what is missing, then render the PNG frames\n"
    "  simulate SCENE    fluid frames -> diffuse caches (spray, foam, bubbles); solver scenes: fluid first\n"
    "  render SCENE      caches -> PNG frames (never simulates)\n"
    "  lookdev SCENE     one frame for every combination of render keys, as a labelled contact sheet\n"
    "  farm chunks|slurm SCENE  frame chunks for GNU parallel, or a Slurm array job (simulation first)\n"
    "  info FILE...      what a particle file or cache holds\n"
    "  report [SCENE]    error against run time of each method, and the stability table -> OUT/report/\n"
    "  compare REF NEW   image regression of two frame sequences (or images): report.html, summary.csv/json\n"
    "run 'spume COMMAND' without arguments for its options.\n";

struct Command {
  const char* name;
  int (*run)(const std::vector<std::string>&);
};

}  // namespace

int main(int argc, char** argv) {
  const Command commands[] = {{"run", spume::command_run},
                             {"simulate", spume::command_simulate},
                             {"render", spume::command_render},
                             {"lookdev", spume::command_lookdev},
                             {"farm", spume::command_farm},
                             {"info", spume::command_info},
                             {"report", spume::command_report},
                             {"compare", spume::command_compare}};
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::vector<std::string> args(argv + 2, argv + argc);
  for (const Command& c : commands) {
    if (std::strcmp(argv[1], c.name) != 0) continue;
    try {
      return c.run(args);
    } catch (const spume::Error& e) {
      std::fprintf(stderr, "spume %s: error: %s\n", c.name, e.what());
      return 1;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "spume %s: internal error: %s\n", c.name, e.what());
      return 3;
    }
  }
  std::fprintf(stderr, "spume: unknown command \"%s\"\n%s", argv[1], kUsage);
  return 2;
}
