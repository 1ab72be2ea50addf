#include "cli_args.h"

#include <charconv>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/frame_spec.h"
#include "core/params.h"

namespace spume::cli {

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

ParsedArgs parse(const std::vector<std::string>& args, const std::vector<OptionSpec>& specs, const std::string& command) {
  ParsedArgs out;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if (a.size() < 3 || a.compare(0, 2, "--") != 0) {
      out.positional.push_back(a);
      continue;
    }
    std::string name = a.substr(2), value;
    bool inline_value = false;
    if (auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1), name = name.substr(0, eq), inline_value = true;
    }
    const OptionSpec* spec = nullptr;
    for (const auto& s : specs)
      if (s.name == name) spec = &s;
    if (!spec) {
      std::string best;
      size_t best_d = SIZE_MAX;
      for (const auto& s : specs)
        if (size_t d = edit_distance(name, s.name); d < best_d) best_d = d, best = s.name;
      fail("spume ", command, ": unknown option --", name,
           best_d <= 3 ? str(" (did you mean --", best, "?)") : std::string(), "\n", usage_lines(specs));
    }
    if (spec->takes_value) {
      if (!inline_value) {
        if (i + 1 >= args.size()) fail("spume ", command, ": --", name, " needs a value");
        value = args[++i];
      }
      if (!spec->repeatable && out.has(name)) fail("spume ", command, ": --", name, " given twice");
      out.values[name].push_back(value);
    } else {
      if (inline_value) fail("spume ", command, ": --", name, " takes no value");
      out.values[name];
    }
  }
  return out;
}

std::string usage_lines(const std::vector<OptionSpec>& specs) {
  std::string text = "options:";
  for (const auto& s : specs) text += str("\n  --", s.name, " ", s.help);
  return text;
}

int parse_int(const std::string& text, const std::string& option, int lo, int hi) {
  int v = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi)
    fail(option, ": \"", text, "\" is not a whole number from ", lo, " to ", hi);
  return v;
}

double parse_double(const std::string& text, const std::string& option) {
  try {
    size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  fail(option, ": \"", text, "\" is not a number");
}

std::pair<int, int> parse_frame_range(const std::string& text, const std::string& option) {
  // The frame-spec grammar everywhere, but only specs that select one unbroken run of frames.
  const std::vector<int> frames = parse_frame_spec(text, 0, std::numeric_limits<int>::max(), option.c_str());
  for (size_t k = 1; k < frames.size(); ++k)
    if (frames[k] != frames[k - 1] + 1)
      fail(option, ": \"", text, "\" is not one unbroken range (frame ", frames[k - 1], " is followed by ", frames[k],
           "); the simulation steps through time from its first frame, so it takes N or A-B");
  return {frames.front(), frames.back()};
}

}  // namespace spume::cli
