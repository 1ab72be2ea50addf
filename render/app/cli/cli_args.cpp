#include "render/app/cli/cli_args.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "sim/core/frame_spec.h"
#include "sim/core/params.h"

namespace spume::cli {
namespace {

// " (did you mean --threads?)" for the option closest to `name` (a few edits away, or the only
// option it is the start of), else "".
std::string option_suggestion(const std::string& name, const std::vector<OptionSpec>& specs) {
  std::string best, prefixed;
  size_t best_d = SIZE_MAX, prefixes = 0;
  for (const auto& s : specs) {
    if (size_t d = edit_distance(name, s.name); d < best_d) best_d = d, best = s.name;
    if (!name.empty() && s.name.rfind(name, 0) == 0) ++prefixes, prefixed = s.name;
  }
  if (best_d <= std::min<size_t>(3, std::max<size_t>(1, name.size() / 2)))
    return str(" (did you mean --", best, "?)");
  if (prefixes == 1) return str(" (did you mean --", prefixed, "?)");
  return "";
}

const OptionSpec* find_spec(const std::string& name, const std::vector<OptionSpec>& specs) {
  for (const auto& s : specs)
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace

std::optional<std::string> ParsedArgs::value(const std::string& name) const {
  auto it = values.find(name);
  if (it == values.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}

const std::vector<std::string>& ParsedArgs::all(const std::string& name) const {
  static const std::vector<std::string> none;
  auto it = values.find(name);
  return it == values.end() ? none : it->second;
}

ParsedArgs parse(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs) {
  ParsedArgs out;
  out.raw = args;
  bool options_ended = false;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    // "-" alone is an operand by convention (standard input); "--" makes the rest operands.
    if (options_ended || a.size() < 2 || a[0] != '-') {
      out.positional.push_back(a);
      continue;
    }
    if (a == "--") {
      options_ended = true;
      continue;
    }
    if (a == "-h" || a == "--help") {
      out.help = true;
      return out;
    }
    if (a[1] != '-') usage_fail("unknown option ", a, " (spume's options are long: --name; -h is --help)");
    std::string name = a.substr(2), value;
    bool inline_value = false;
    if (auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1), name = name.substr(0, eq), inline_value = true;
    }
    const OptionSpec* spec = find_spec(name, specs);
    if (!spec) usage_fail("unknown option --", name, option_suggestion(name, specs));
    if (spec->takes_value()) {
      if (!inline_value) {
        if (i + 1 >= args.size()) usage_fail("--", name, " needs a value: --", name, " ", spec->value);
        value = args[++i];
      }
      if (!spec->repeatable && out.has(name))
        usage_fail("--", name, " given twice (\"", out.values[name].back(), "\" and \"", value, "\"); give it once");
      out.values[name].push_back(value);
    } else {
      if (inline_value) usage_fail("--", name, " takes no value (found --", name, "=", value, ")");
      out.values[name];
    }
  }
  return out;
}

int parse_int(const std::string& text, const std::string& option, int lo, int hi) {
  int v = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi)
    usage_fail(option, ": \"", text, "\" is not a whole number from ", lo, " to ", hi);
  return v;
}

double parse_double(const std::string& text, const std::string& option) {
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  usage_fail(option, ": \"", text, "\" is not a number");
}

void check_frame_spec(const std::string& text, const std::string& option) {
  as_usage([&] { parse_frame_spec(text, 0, std::numeric_limits<int>::max(), option.c_str()); });
}

std::pair<int, int> parse_frame_range(const std::string& text, const std::string& option) {
  // The frame-spec grammar everywhere, but only specs that select one unbroken run of frames.
  const std::vector<int> frames =
      as_usage([&] { return parse_frame_spec(text, 0, std::numeric_limits<int>::max(), option.c_str()); });
  for (size_t k = 1; k < frames.size(); ++k)
    if (frames[k] != frames[k - 1] + 1)
      usage_fail(option, ": \"", text, "\" is not one unbroken range (frame ", frames[k - 1], " is followed by ",
                 frames[k], "); the simulation steps through time from its first frame, so it takes N or A-B");
  return {frames.front(), frames.back()};
}

}  // namespace spume::cli
