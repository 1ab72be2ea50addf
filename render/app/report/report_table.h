#pragma once
// A study's table: named columns, rows of cells already formatted as text, written as CSV (RFC 4180
// quoting) and as a markdown table (pipes and newlines escaped, so any cell text stays in its cell).
#include <string>
#include <vector>

namespace spume::report {

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;

  // Throws Error when the row's cell count differs from the column count.
  void add_row(std::vector<std::string> cells);
};

// A number for a table: %.4g, and "nan"/"inf" spelled out (never an empty cell).
std::string num(double value, int significant = 4);

std::string csv_cell(const std::string& text);       // quoted when it holds , " CR or LF
std::string markdown_cell(const std::string& text);   // | -> \|, \ -> \\, newlines -> <br>
std::string to_csv(const Table& table);
std::string to_markdown(const Table& table);

}  // namespace spume::report
