#include "sim/core/frame_spec.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <limits>
#include <string>

#include "sim/core/error.h"

namespace spume {
namespace {

constexpr const char* kAcceptedForms =
    "accepted forms: N, A-B, A-B:STEP, or a comma-separated list of those such as 1-3,5,10-20 "
    "(frames are integers >= 0, no spaces)";

struct Context {
  std::string_view spec;
  const char* what;
};

[[noreturn]] void malformed(const Context& ctx, std::string_view item, std::string_view why) {
  if (item == ctx.spec)
    fail(ctx.what, ": \"", ctx.spec, "\" ", why, "; ", kAcceptedForms);
  fail(ctx.what, ": item \"", item, "\" of \"", ctx.spec, "\" ", why, "; ", kAcceptedForms);
}

// A run of decimal digits that fits an int; anything else (sign, space, empty, letters) is malformed.
int parse_number(const Context& ctx, std::string_view item, std::string_view digits, const char* role) {
  if (digits.empty()) malformed(ctx, item, str("has no ", role));
  if (!std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    if (digits.front() == '-' || item.front() == '-') malformed(ctx, item, "has a negative frame");
    malformed(ctx, item, str("has ", role, " \"", digits, "\", not a whole number"));
  }
  int value = 0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error == std::errc::result_out_of_range)
    malformed(ctx, item, str("has ", role, " ", digits, ", larger than the largest allowed (",
                             std::numeric_limits<int>::max(), ")"));
  if (error != std::errc() || end != digits.data() + digits.size()) malformed(ctx, item, "is not a number");
  return value;
}

struct Item {
  int start, end, step;
};

Item parse_item(const Context& ctx, std::string_view item) {
  if (item.find_first_of(" \t\r\n") != std::string_view::npos) malformed(ctx, item, "contains white space");
  if (item.front() == '-') malformed(ctx, item, "has a negative frame");
  const size_t dash = item.find('-');
  const size_t colon = item.find(':');
  if (dash == std::string_view::npos) {
    if (colon != std::string_view::npos) malformed(ctx, item, "has a step but no range (write A-B:STEP)");
    const int f = parse_number(ctx, item, item, "frame");
    return {f, f, 1};
  }
  if (colon != std::string_view::npos && colon < dash) malformed(ctx, item, "has its step before the range");
  const std::string_view a = item.substr(0, dash);
  const std::string_view rest = item.substr(dash + 1);
  const size_t rest_colon = rest.find(':');
  const std::string_view b = rest.substr(0, rest_colon);
  const int start = parse_number(ctx, item, a, "start");
  const int end = parse_number(ctx, item, b, "end");
  int step = 1;
  if (rest_colon != std::string_view::npos) {
    step = parse_number(ctx, item, rest.substr(rest_colon + 1), "step");
    if (step < 1) malformed(ctx, item, "has step 0; the step must be at least 1");
  }
  if (end < start) malformed(ctx, item, str("ends (", end, ") before it starts (", start, ")"));
  return {start, end, step};
}

}  // namespace

std::vector<int> parse_frame_spec(std::string_view spec, int first, int last, const char* what) {
  const Context ctx{spec, what};
  if (first > last) fail(what, ": the available frames ", first, "-", last, " are empty (first after last)");
  if (spec.empty()) fail(what, ": the frame spec is empty; ", kAcceptedForms);

  std::vector<int> frames;
  size_t pos = 0;
  while (true) {
    const size_t comma = spec.find(',', pos);
    const std::string_view item = spec.substr(pos, comma == std::string_view::npos ? spec.npos : comma - pos);
    if (item.empty()) malformed(ctx, spec, "has an empty item (a stray comma)");
    const Item it = parse_item(ctx, item);
    // Clip to [first, last] in 64 bits: the first frame of the item's progression at or after `first`.
    int64_t f = it.start;
    if (f < first) f += (int64_t(first) - f + it.step - 1) / it.step * it.step;
    const int64_t stop = std::min<int64_t>(it.end, last);
    for (; f <= stop; f += it.step) frames.push_back(int(f));
    if (comma == std::string_view::npos) break;
    pos = comma + 1;
  }
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  if (frames.empty()) fail(what, ": \"", spec, "\" selects no frame in the available range ", first, "-", last);
  return frames;
}

}  // namespace spume
