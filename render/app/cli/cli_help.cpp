#include "render/app/cli/cli_help.h"

#include <algorithm>
#include <sstream>

namespace spume::cli {
namespace {

// Greedy word wrap; a word longer than the line stands alone rather than being cut.
std::vector<std::string> wrap_words(const std::string& text, size_t width) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string line;
  for (std::string word; words >> word;) {
    if (!line.empty() && line.size() + 1 + word.size() > width) lines.push_back(std::move(line)), line.clear();
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

}  // namespace

std::string aligned_table(const std::vector<std::pair<std::string, std::string>>& rows, size_t width) {
  constexpr size_t kIndent = 2, kGap = 2, kNarrowest = 30;
  size_t left = 0;
  for (const auto& row : rows) left = std::max(left, row.first.size());
  const size_t column = kIndent + left + kGap;
  const size_t room = std::max(kNarrowest, width > column ? width - column : 0);
  std::string text;
  for (const auto& [cell, description] : rows) {
    const std::vector<std::string> lines = wrap_words(description, room);
    text += std::string(kIndent, ' ') + cell;
    for (size_t k = 0; k < lines.size(); ++k) {
      const size_t at = k == 0 ? kIndent + cell.size() : 0;
      text += (lines[k].empty() ? "" : std::string(column - at, ' ') + lines[k]) + "\n";
    }
  }
  return text;
}

std::string option_table(const std::vector<OptionSpec>& options) {
  std::vector<std::pair<std::string, std::string>> rows = {{"-h, --help", "print this help and exit"}};
  for (const OptionSpec& o : options)
    rows.emplace_back("--" + o.name + (o.takes_value() ? " " + o.value : ""),
                      o.help + (o.repeatable ? " (repeatable)" : ""));
  return aligned_table(rows);
}

std::string help_text(const CommandSpec& spec) {
  std::string text;
  for (size_t k = 0; k < spec.forms.size(); ++k)
    text += str(k == 0 ? "usage: " : "   or: ", "spume ", spec.name, " ", spec.forms[k], "\n");
  for (const auto& line : wrap_words(spec.summary, 100)) text += line + "\n";
  text += "\noptions:\n" + option_table(spec.options);
  if (!spec.notes.empty()) text += "\n";
  for (const auto& line : spec.notes) text += line + "\n";
  return text;
}

}  // namespace spume::cli
