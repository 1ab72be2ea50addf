#pragma once
// Help text of the commands: a usage line per form, what the command does, and the options as a
// two-column table whose descriptions all start in one column, computed from the option specs.
#include <string>
#include <utility>
#include <vector>

#include "render/app/cli/cli_args.h"

namespace spume::cli {

struct CommandSpec {
  std::string name;                   // as typed after "spume": "run", "farm slurm"
  std::vector<std::string> forms;     // operands and options of each usage line, e.g. "SCENE.json [options]"
  std::string summary;                // what it does (the top-level command list shows it too)
  std::vector<OptionSpec> options;    // -h/--help is implied
  std::vector<std::string> notes;     // lines after the table, e.g. an example
  size_t max_operands = 1;            // more positional arguments are a usage error
  bool runs_without_arguments = false;  // else `spume NAME` alone prints the help and exits 2
};

// Rows of (left, right) as lines "  left   right", the right column starting where the longest left
// cell ends plus two spaces; right cells wrap at `width` characters, continuing in their column.
std::string aligned_table(const std::vector<std::pair<std::string, std::string>>& rows, size_t width = 100);

// The options table, -h/--help first; repeatable options say so.
std::string option_table(const std::vector<OptionSpec>& options);

// usage lines, summary, "options:" and the table, notes.
std::string help_text(const CommandSpec& spec);

}  // namespace spume::cli
