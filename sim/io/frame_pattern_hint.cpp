#include "sim/io/frame_pattern_hint.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <system_error>
#include <vector>

#include "sim/core/error.h"
#include "sim/io/frame_pattern.h"

namespace spume {
namespace {

namespace fs = std::filesystem;

// A file name split around its frame number: the digits before `suffix` when it ends with the
// pattern's suffix, else its last run of digits.
struct NumberedName {
  std::string prefix, digits, suffix;
};

std::optional<NumberedName> split_numbered(const std::string& name, const std::string& pattern_suffix) {
  auto digits_before = [&](size_t end) -> std::optional<NumberedName> {
    size_t begin = end;
    while (begin > 0 && std::isdigit(static_cast<unsigned char>(name[begin - 1]))) --begin;
    if (begin == end) return std::nullopt;
    return NumberedName{name.substr(0, begin), name.substr(begin, end - begin), name.substr(end)};
  };
  if (name.size() > pattern_suffix.size() && name.compare(name.size() - pattern_suffix.size(), pattern_suffix.size(), pattern_suffix) == 0)
    if (auto split = digits_before(name.size() - pattern_suffix.size())) return split;
  for (size_t end = name.size(); end > 0; --end)
    if (std::isdigit(static_cast<unsigned char>(name[end - 1]))) return digits_before(end);
  return std::nullopt;
}

// The zero-padding that names all of `numbers`: 0 when none has a leading zero, else the common
// length of those that do (longer numbers never start with 0); nullopt when the files mix paddings.
std::optional<int> common_padding(const std::vector<std::string>& numbers) {
  size_t shortest = SIZE_MAX;
  for (const std::string& d : numbers) shortest = std::min(shortest, d.size());
  bool padded = false;
  for (const std::string& d : numbers)
    if (d.size() > 1 && d[0] == '0') {
      if (d.size() != shortest) return std::nullopt;
      padded = true;
    }
  if (!padded) return 0;
  for (const std::string& d : numbers)
    if (d.size() > shortest && d[0] == '0') return std::nullopt;
  return int(shortest);
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

struct Candidate {
  std::string pattern;  // with the folder as the user wrote it
  FramePatternParts parts;
  std::vector<int> frames;
  int likeness = 0;  // 3 the same name but the padding, 2 the same but for case, 1 the same ending, 0 other
};

std::string frames_text(const std::vector<int>& frames) {
  return str(frames.size(), frames.size() == 1 ? " file" : " files", ", frame", frames.size() == 1 ? " " : "s ",
             frames.front(), frames.size() == 1 ? "" : str("-", frames.back()));
}

std::string padding_text(int width) {
  return width == 0 ? "without zero padding" : str("zero-padded to ", width, " digits");
}

}  // namespace

std::string unmatched_pattern_hint(const std::string& pattern) {
  FramePatternParts wanted;
  std::string name_pattern, folder_text;
  fs::path dir;
  try {
    const fs::path full(pattern);
    name_pattern = full.filename().string();
    wanted = parse_frame_pattern(name_pattern);
    folder_text = pattern.substr(0, pattern.size() - name_pattern.size());
    dir = full.has_parent_path() ? full.parent_path() : fs::path(".");
  } catch (const Error&) {
    return "";
  }
  std::error_code ec;
  std::vector<std::string> names;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) || it->is_symlink(ec)) names.push_back(it->path().filename().string());
  if (ec) return "";
  std::sort(names.begin(), names.end());
  const std::string where = dir.string();
  if (names.empty()) return str("; the folder ", where, " holds no files");

  std::map<std::pair<std::string, std::string>, std::vector<std::string>> numbered;  // (prefix, suffix) -> numbers
  for (const std::string& name : names)
    if (auto split = split_numbered(name, wanted.suffix)) numbered[{split->prefix, split->suffix}].push_back(split->digits);

  std::vector<Candidate> candidates;
  for (const auto& [affixes, numbers] : numbered) {
    const std::optional<int> width = common_padding(numbers);
    if (!width) continue;
    Candidate c;
    c.parts = FramePatternParts{affixes.first, affixes.second, *width, wanted.style};
    const std::string name = compose_frame_pattern(c.parts);
    if (name.empty()) continue;
    c.pattern = folder_text + name;
    try {
      c.frames = find_pattern_frames(c.pattern);
    } catch (const Error&) {
      continue;
    }
    if (c.frames.empty()) continue;
    const bool same = affixes.first == wanted.prefix && affixes.second == wanted.suffix;
    const bool same_but_case = lower(affixes.first) == lower(wanted.prefix) && lower(affixes.second) == lower(wanted.suffix);
    c.likeness = same ? 3 : same_but_case ? 2 : lower(affixes.second) == lower(wanted.suffix) ? 1 : 0;
    candidates.push_back(std::move(c));
  }
  std::stable_sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return a.likeness != b.likeness ? a.likeness > b.likeness : a.frames.size() > b.frames.size();
  });

  if (candidates.empty()) {
    std::string listing;
    for (size_t k = 0; k < std::min<size_t>(names.size(), 3); ++k) listing += str(k ? ", " : "", names[k]);
    return str("; the folder ", where, " holds ", names.size(), names.size() == 1 ? " file" : " files", ", ",
               numbered.empty() ? "none numbered" : "none in a sequence one pattern can name (zero padding mixed, or "
                                                    "a '#' in the name)",
               " (", listing, names.size() > 3 ? ", ..." : "", ")");
  }
  const Candidate& best = candidates.front();
  if (best.likeness == 3)
    return str("; the files there are numbered ", padding_text(best.parts.width), " (", name_pattern, " wants them ",
               padding_text(wanted.width), "): ", best.pattern, " matches ", frames_text(best.frames));
  std::string text = str("; in ", where, ": ", best.pattern, " matches ", frames_text(best.frames));
  for (size_t k = 1; k < std::min<size_t>(candidates.size(), 3); ++k)
    text += str(", ", candidates[k].pattern, " ", frames_text(candidates[k].frames));
  if (candidates.size() > 3) text += str(", and ", candidates.size() - 3, " more numbered sequences");
  return text;
}

}  // namespace spume
