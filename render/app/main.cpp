// spume: spray, foam and bubbles for particle fluids (Ihmsen et al. 2012), simulated and rendered.
// Finds the command, answers -h/--help and --version, and turns what a command throws into its exit
// status and one message that names the command once.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "render/app/commands.h"
#include "render/app/read_check_command.h"
#include "render/app/startup_guard.h"
#include "sim/core/error.h"
#include "sim/core/messages.h"
#include "sim/core/out_of_memory.h"
#include "sim/core/thread_budget.h"
#include "sim/core/params.h"
#include "sim/io/contained_read.h"
#include "render/app/version_info.h"

namespace spume {
namespace {

std::vector<Command> all_commands() {
  return {cmd_run(),         cmd_simulate(),   cmd_render(), cmd_lookdev(),
          cmd_farm_chunks(), cmd_farm_slurm(), cmd_info(),   cmd_report(), cmd_compare(), cmd_keys()};
}

bool is_help(const std::string& a) { return a == "-h" || a == "--help"; }

// The commands whose name starts with `prefix` ("" for all, "farm " for the farm subcommands), as a
// table of their names and summaries (their operands are in their own help).
std::string command_table(const std::vector<Command>& commands, const std::string& prefix) {
  std::vector<std::pair<std::string, std::string>> rows;
  for (const Command& c : commands)
    if (c.spec.name.rfind(prefix, 0) == 0) rows.emplace_back(c.spec.name, c.spec.summary);
  return cli::aligned_table(rows);
}

std::string top_usage(const std::vector<Command>& commands) {
  return "usage: spume COMMAND [options]\n       spume --version\ncommands:\n" + command_table(commands, "") +
         "'spume COMMAND --help' prints the options of a command.\n";
}

std::string group_usage(const std::vector<Command>& commands, const std::string& group) {
  return str("usage: spume ", group, " SUBCOMMAND [options]\nsubcommands:\n", command_table(commands, group + " "),
             "'spume ", group, " SUBCOMMAND --help' prints its options.\n");
}

// " (did you mean \"run\"?)" for a mistyped command word.
std::string closest_word(const std::string& word, const std::vector<std::string>& known) {
  std::string best;
  size_t best_d = SIZE_MAX;
  for (const auto& k : known)
    if (size_t d = edit_distance(word, k); d < best_d) best_d = d, best = k;
  return best_d <= 2 ? str(" (did you mean \"", best, "\"?)") : "";
}

int usage_error(const std::string& command, const std::string& message) {
  std::fprintf(stderr, "spume %s: error: %s\nTry 'spume %s --help' for more information.\n", command.c_str(),
               message.c_str(), command.c_str());
  return cli::kExitUsage;
}

int run(const Command& command, const std::vector<std::string>& args) {
  const cli::CommandSpec& spec = command.spec;
  if (args.empty() && !spec.runs_without_arguments) {
    std::fputs(cli::help_text(spec).c_str(), stderr);
    return cli::kExitUsage;
  }
  const char* name = spec.name.c_str();
  try {
    const cli::ParsedArgs parsed = cli::parse(args, spec.options);
    if (parsed.help) {
      std::fputs(cli::help_text(spec).c_str(), stdout);
      return cli::kExitOk;
    }
    // --quiet hides progress and notes in every stage, never warnings (sim/core/messages.h).
    messages::set_quiet(parsed.has("quiet"));
    if (parsed.positional.size() > spec.max_operands)
      cli::usage_fail("expected ", spec.forms.front(), "; found ", parsed.positional.size(),
                      " operands (", parsed.positional[spec.max_operands], " is one too many)");
    return command.run(parsed);
  } catch (const cli::UsageError& e) {
    return usage_error(spec.name, e.what());
  } catch (const Error& e) {
    std::fprintf(stderr, "spume %s: error: %s\n", name, e.what());
    return cli::kExitError;
  } catch (const std::bad_alloc&) {  // one the reading and frame boundaries did not put a name to
    std::fprintf(stderr, "spume %s: error: %s\n", name, out_of_memory_message("").c_str());
    return cli::kExitError;
  } catch (const std::system_error& e) {
    if (e.code() != std::errc::resource_unavailable_try_again) {
      std::fprintf(stderr, "spume %s: internal error: %s\n", name, e.what());
      return cli::kExitInternal;
    }
    std::fprintf(stderr, "spume %s: error: could not start a thread (%s)%s\n", name, e.what(),
                 memory_situation().c_str());
    return cli::kExitError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "spume %s: internal error: %s\n", name, e.what());
    return cli::kExitInternal;
  }
}

int dispatch(const std::vector<std::string>& argv) {
  const std::vector<Command> commands = all_commands();
  if (argv.empty()) {
    std::fputs(top_usage(commands).c_str(), stderr);
    return cli::kExitUsage;
  }
  const std::string& word = argv[0];
  if (is_help(word)) {
    std::fputs(top_usage(commands).c_str(), stdout);
    return cli::kExitOk;
  }
  if (word == "--version" || word == "-V") {
    std::fputs(version_text().c_str(), stdout);
    return cli::kExitOk;
  }
  std::vector<std::string> words;  // the first word of every command, once
  for (const Command& c : commands) {
    const std::string first = c.spec.name.substr(0, c.spec.name.find(' '));
    if (words.empty() || words.back() != first) words.push_back(first);
    if (c.spec.name == word) return run(c, {argv.begin() + 1, argv.end()});
  }
  if (std::find(words.begin(), words.end(), word) != words.end()) {  // a group: farm chunks|slurm
    if (argv.size() < 2 || is_help(argv[1])) {
      std::fputs(group_usage(commands, word).c_str(), argv.size() < 2 ? stderr : stdout);
      return argv.size() < 2 ? cli::kExitUsage : cli::kExitOk;
    }
    std::vector<std::string> subcommands;
    for (const Command& c : commands) {
      if (c.spec.name == word + " " + argv[1]) return run(c, {argv.begin() + 2, argv.end()});
      if (c.spec.name.rfind(word + " ", 0) == 0) subcommands.push_back(c.spec.name.substr(word.size() + 1));
    }
    std::fprintf(stderr, "spume %s: error: unknown subcommand \"%s\"%s\n%s", word.c_str(), argv[1].c_str(),
                 closest_word(argv[1], subcommands).c_str(), group_usage(commands, word).c_str());
    return cli::kExitUsage;
  }
  std::fprintf(stderr, "spume: error: unknown command \"%s\"%s\n%s", word.c_str(), closest_word(word, words).c_str(),
               top_usage(commands).c_str());
  return cli::kExitUsage;
}

}  // namespace
}  // namespace spume

int main(int argc, char** argv) {
  spume::end_startup_guard();
  if (argc > 1 && std::string(argv[1]) == spume::kReadCheckWord) return spume::run_read_check({argv + 2, argv + argc});
  spume::limit_threads_to_address_space();
  // Files OpenVDB reads are read first by a child of this executable (sim/io/contained_read.h).
  std::error_code self_error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", self_error);
  spume::contain_untrusted_reads(self_error ? std::filesystem::path(argv[0]) : self);
  return spume::dispatch({argv + 1, argv + argc});
}
