#include "sim/io/frame_pattern.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <system_error>

#include "sim/core/error.h"

namespace spume {
namespace {

using ParsedPattern = FramePatternParts;

// Scans the pattern. With strict = false it only counts placeholders and never throws.
int scan(const std::string& pattern, bool strict, ParsedPattern* out) {
  int placeholders = 0;
  std::string literal;
  auto placeholder = [&](int width, PlaceholderStyle style) {
    if (++placeholders == 2 && strict)
      fail("frame pattern '", pattern, "': more than one frame placeholder; exactly one of %d, %0Nd, #### or $F/$FN allowed");
    if (out) {
      out->prefix = literal;
      out->width = width <= 1 ? 0 : width;
      out->style = style;
    }
    literal.clear();
  };
  for (size_t i = 0; i < pattern.size();) {
    const char c = pattern[i];
    if (c == '$' && i + 1 < pattern.size() && pattern[i + 1] == 'F') {
      // Houdini's $F (unpadded) and $F2..$F9 (padded), as its file caches name frames; $FF, $FPS and the
      // like are other variables, kept as text.
      const size_t j = i + 2;
      const bool digit = j < pattern.size() && pattern[j] >= '1' && pattern[j] <= '9';
      const bool word = j < pattern.size() && (std::isalnum(static_cast<unsigned char>(pattern[j])) || pattern[j] == '_');
      if (digit) {
        placeholder(pattern[j] - '0', PlaceholderStyle::Houdini);
        i = j + 1;
        continue;
      }
      if (!word) {
        placeholder(0, PlaceholderStyle::Houdini);
        i = j;
        continue;
      }
    }
    if (c == '#') {
      size_t j = i;
      while (j < pattern.size() && pattern[j] == '#') ++j;
      placeholder(int(j - i), PlaceholderStyle::Hashes);
      i = j;
    } else if (c == '%') {
      if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
        literal += '%';
        i += 2;
        continue;
      }
      if (i + 1 < pattern.size() && pattern[i + 1] == 'd') {
        placeholder(0, PlaceholderStyle::Printf);
        i += 2;
        continue;
      }
      size_t j = i + 1;
      while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j]))) ++j;
      const bool padded = j > i + 2 && pattern[i + 1] == '0' && j < pattern.size() && pattern[j] == 'd';
      int width = 0;
      if (padded) std::from_chars(pattern.data() + i + 2, pattern.data() + j, width);
      if (!padded || width < 1 || width > 20) {
        if (!strict) {
          literal += c;
          ++i;
          continue;
        }
        fail("frame pattern '", pattern, "': unsupported sequence '", pattern.substr(i, std::min(j + 1, pattern.size()) - i),
             "' at position ", i, "; allowed %d, %0Nd (N = 1..20), a run of '#', or %% for a literal '%'");
      }
      placeholder(width, PlaceholderStyle::Printf);
      i = j + 1;
    } else {
      literal += c;
      ++i;
    }
  }
  if (out && placeholders > 0) out->suffix = literal;
  if (strict && placeholders == 0)
    fail("frame pattern '", pattern, "': no frame placeholder; use %d, %0Nd (e.g. %04d), #### or Houdini's $F/$F4 for the frame number");
  return placeholders;
}

std::string format_number(int frame, int width) {
  std::string digits = std::to_string(frame);
  if (int(digits.size()) < width) digits.insert(0, size_t(width) - digits.size(), '0');
  return digits;
}

}  // namespace

FramePatternParts parse_frame_pattern(const std::string& pattern) {
  ParsedPattern p;
  scan(pattern, true, &p);
  return p;
}

std::string compose_frame_pattern(const FramePatternParts& parts) {
  const int width = parts.width <= 1 ? 0 : parts.width;
  auto compose = [&](PlaceholderStyle style) -> std::string {
    auto escaped = [&](const std::string& text) {
      if (style != PlaceholderStyle::Printf) return text;
      std::string out;
      for (char c : text) out += c == '%' ? std::string("%%") : std::string(1, c);
      return out;
    };
    std::string placeholder;
    switch (style) {
      case PlaceholderStyle::Printf:
        if (width > 20) return "";
        placeholder = width == 0 ? "%d" : str("%0", width, "d");
        break;
      case PlaceholderStyle::Hashes: placeholder = std::string(size_t(std::max(width, 1)), '#'); break;
      case PlaceholderStyle::Houdini:
        if (width > 9) return "";
        placeholder = width == 0 ? "$F" : str("$F", width);
        break;
    }
    std::string text = escaped(parts.prefix) + placeholder + escaped(parts.suffix);
    // Only a pattern that reads back as these parts: the text may hold a '#' or a "$F" of its own.
    ParsedPattern back;
    try {
      scan(text, true, &back);
    } catch (const Error&) {
      return "";
    }
    return back.prefix == parts.prefix && back.suffix == parts.suffix && back.width == width ? text : "";
  };
  std::string text = compose(parts.style);
  return text.empty() && parts.style != PlaceholderStyle::Printf ? compose(PlaceholderStyle::Printf) : text;
}

std::string canonical_frame_pattern(const std::string& pattern) {
  namespace fs = std::filesystem;
  const fs::path full(pattern);
  FramePatternParts parts;
  try {
    parts = parse_frame_pattern(full.filename().string());
  } catch (const Error&) {
    return pattern;
  }
  parts.style = PlaceholderStyle::Printf;
  const std::string name = compose_frame_pattern(parts);
  if (name.empty()) return pattern;
  std::error_code ec;
  const fs::path dir = full.has_parent_path() ? full.parent_path() : fs::path(".");
  fs::path folder = fs::weakly_canonical(dir, ec);
  if (ec) folder = fs::absolute(dir, ec).lexically_normal();
  return (folder / name).string();
}

bool is_frame_pattern(const std::string& pattern) { return scan(pattern, false, nullptr) > 0; }

std::string expand_frame_pattern(const std::string& pattern, int frame) {
  ParsedPattern p;
  scan(pattern, true, &p);
  if (frame < 0) fail("frame pattern '", pattern, "': frame ", frame, " is negative; frame numbers must be >= 0");
  return p.prefix + format_number(frame, p.width) + p.suffix;
}

std::vector<int> find_pattern_frames(const std::string& pattern) {
  namespace fs = std::filesystem;
  ParsedPattern p;
  scan(pattern, true, &p);
  const fs::path full(pattern);
  const std::string name_pattern = full.filename().string();
  if (scan(name_pattern, false, nullptr) == 0)
    fail("frame pattern '", pattern, "': the frame placeholder must be in the file name, not in a directory");
  ParsedPattern np;
  scan(name_pattern, true, &np);
  const fs::path dir = full.has_parent_path() ? full.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    fail("frame pattern '", pattern, "': directory ", dir.string(), " does not exist");

  std::vector<int> frames;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= np.prefix.size() + np.suffix.size()) continue;
    if (name.compare(0, np.prefix.size(), np.prefix) != 0) continue;
    if (name.compare(name.size() - np.suffix.size(), np.suffix.size(), np.suffix) != 0) continue;
    const std::string digits = name.substr(np.prefix.size(), name.size() - np.prefix.size() - np.suffix.size());
    if (!std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); })) continue;
    int frame = 0;
    const auto [ptr, err] = std::from_chars(digits.data(), digits.data() + digits.size(), frame);
    if (err != std::errc() || ptr != digits.data() + digits.size()) continue;  // too many digits for an int
    // Only names the expander would produce, so every listed frame can be opened by number.
    if (format_number(frame, np.width) != digits) continue;
    if (!it->is_regular_file(ec) && !it->is_symlink(ec)) continue;
    frames.push_back(frame);
  }
  if (ec) fail("frame pattern '", pattern, "': cannot list directory ", dir.string(), ": ", ec.message());
  std::sort(frames.begin(), frames.end());
  return frames;
}

}  // namespace spume
