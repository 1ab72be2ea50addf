#pragma once
// A small command-line parser: positional arguments, --flags, --options VALUE (or --option=VALUE),
// and repeatable options (--set). Unknown options are errors naming the option and the allowed ones.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace spume::cli {

struct OptionSpec {
  std::string name;         // without dashes
  bool takes_value = false;
  bool repeatable = false;
  std::string help;         // "FILE  what it does"
};

struct ParsedArgs {
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> values;  // option -> values in order
  bool has(const std::string& name) const { return values.count(name) > 0; }
  std::optional<std::string> value(const std::string& name) const;
  const std::vector<std::string>& all(const std::string& name) const;
};

ParsedArgs parse(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs, const std::string& command);

std::string usage_lines(const std::vector<OptionSpec>& specs);

// A frame spec (core/frame_spec.h) that selects one unbroken run, e.g. "7", "12-40" or "0-3,4-9" ->
// inclusive range; steps and gaps are errors naming the option. For the sequential simulation.
std::pair<int, int> parse_frame_range(const std::string& text, const std::string& option);
int parse_int(const std::string& text, const std::string& option, int lo, int hi);
double parse_double(const std::string& text, const std::string& option);

}  // namespace spume::cli
