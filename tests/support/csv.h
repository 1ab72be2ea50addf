#pragma once
// CSV files as spume writes them (stats.csv, summary.csv, the report's tables): rows of cells, quoted
// cells ("a,b", and "" for a quote) read as RFC 4180 writes them.
#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/files.h"

namespace spume::testing {

inline std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path) {
  std::vector<std::vector<std::string>> rows;
  const std::string text = read_file(path);
  std::vector<std::string> row;
  std::string cell;
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') cell += '"', ++i;
      else if (c == '"') quoted = false;
      else cell += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      row.push_back(cell), cell.clear();
    } else if (c == '\n') {
      row.push_back(cell), cell.clear();
      rows.push_back(row), row.clear();
    } else {
      cell += c;
    }
  }
  if (!cell.empty() || !row.empty()) rows.push_back((row.push_back(cell), row));  // a last line without '\n'
  return rows;
}

// The sum of column `name` over every row after the header (0 when there is no such column).
inline double column_sum(const std::vector<std::vector<std::string>>& rows, const std::string& name) {
  if (rows.empty()) return 0;
  size_t column = 0;
  while (column < rows[0].size() && rows[0][column] != name) ++column;
  if (column == rows[0].size()) return 0;
  double sum = 0;
  for (size_t i = 1; i < rows.size(); ++i)
    if (column < rows[i].size()) sum += std::stod(rows[i][column]);
  return sum;
}

}  // namespace spume::testing
