#pragma once
// A small command-line parser: positional arguments, --flags, --options VALUE (or --option=VALUE),
// repeatable options (--set), -h/--help, and "--" ending the options. Mistakes in the command line
// itself throw UsageError, which main turns into exit status 2 (see kExit* below).
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sim/core/error.h"

namespace spume::cli {

// Exit statuses of every spume command, in one place (README, Commands).
constexpr int kExitOk = 0;
constexpr int kExitError = 1;     // the scene, an input file or a stage failed (spume::Error)
constexpr int kExitUsage = 2;     // the command line is wrong (UsageError): fix the options
constexpr int kExitInternal = 3;  // a bug or the machine (std::exception that is not an Error)

// The command line is wrong: unknown option, missing or repeated value, wrong operand count, an
// option value that does not parse. Messages never name the command; main prefixes it once.
class UsageError : public Error {
 public:
  using Error::Error;
};

template <typename... Parts>
[[noreturn]] void usage_fail(Parts&&... parts) {
  throw UsageError(str(std::forward<Parts>(parts)...));
}

// Runs fn, turning an Error into a UsageError: for checks shared with scene files (frame specs,
// --set paths) whose failure, on the command line, is the command line's fault.
template <typename Fn>
decltype(auto) as_usage(Fn&& fn) {
  try {
    return std::forward<Fn>(fn)();
  } catch (const UsageError&) {
    throw;
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
}

struct OptionSpec {
  std::string name;         // without dashes
  std::string value;        // placeholder shown in help, e.g. "DIR"; empty for a flag
  std::string help;         // what it does
  bool repeatable = false;  // a value option that may be given many times (--set)
  bool takes_value() const { return !value.empty(); }
};

// --quiet, alike on every command (sim/core/messages.h says what it hides).
inline OptionSpec quiet_option() {
  return {"quiet", "", "no progress and no notes on stderr; warnings and errors are always printed"};
}

struct ParsedArgs {
  std::vector<std::string> raw;  // as typed, for records of the command (report.md)
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> values;  // option -> values in order
  bool help = false;                                       // -h or --help was given
  bool has(const std::string& name) const { return values.count(name) > 0; }
  std::optional<std::string> value(const std::string& name) const;
  const std::vector<std::string>& all(const std::string& name) const;
};

// Stops at -h/--help (help = true) so that a help request never fails on what follows it.
ParsedArgs parse(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs);

// A frame spec (core/frame_spec.h) that selects one unbroken run, e.g. "7", "12-40" or "0-3,4-9" ->
// inclusive range; steps and gaps are errors naming the option. For the sequential simulation.
std::pair<int, int> parse_frame_range(const std::string& text, const std::string& option);
// Checks the frame-spec syntax of an option before any work (the frames are clipped later).
void check_frame_spec(const std::string& text, const std::string& option);
int parse_int(const std::string& text, const std::string& option, int lo, int hi);
double parse_double(const std::string& text, const std::string& option);

}  // namespace spume::cli
