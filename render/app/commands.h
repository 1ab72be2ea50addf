#pragma once
// The spume commands. Each is its help (usage, options) and a function that runs it on the parsed
// command line and returns the exit status; main parses, answers -h/--help, and reports what is
// thrown: spume::Error exits 1, cli::UsageError 2, anything else 3 (cli_args.h).
#include "render/app/cli/cli_help.h"

namespace spume {

struct Command {
  cli::CommandSpec spec;
  int (*run)(const cli::ParsedArgs& args);
};

Command cmd_run();
Command cmd_simulate();
Command cmd_render();
Command cmd_lookdev();
Command cmd_farm_chunks();
Command cmd_farm_slurm();
Command cmd_info();
Command cmd_report();
Command cmd_compare();
Command cmd_keys();

}  // namespace spume
