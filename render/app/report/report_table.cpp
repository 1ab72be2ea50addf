#include "render/app/report/report_table.h"

#include <cmath>
#include <cstdio>

#include "sim/core/error.h"

namespace spume::report {

void Table::add_row(std::vector<std::string> cells) {
  if (cells.size() != columns.size())
    fail("report table: a row has ", cells.size(), " cells for ", columns.size(), " columns");
  rows.push_back(std::move(cells));
}

std::string num(double value, int significant) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", significant, value);
  return buffer;
}

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

std::string markdown_cell(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '|' || c == '\\') out += '\\', out += c;
    else if (c == '\r') continue;
    else if (c == '\n') out += "<br>";
    else out += c;
  }
  return out;
}

std::string to_csv(const Table& t) {
  std::string out;
  auto line = [&](const std::vector<std::string>& cells) {
    for (size_t i = 0; i < cells.size(); ++i) {
      if (i) out += ',';
      out += csv_cell(cells[i]);
    }
    out += '\n';
  };
  line(t.columns);
  for (const auto& row : t.rows) line(row);
  return out;
}

std::string to_markdown(const Table& t) {
  std::string out;
  auto line = [&](const std::vector<std::string>& cells) {
    out += '|';
    for (const auto& c : cells) out += ' ' + markdown_cell(c) + " |";
    out += '\n';
  };
  line(t.columns);
  out += '|';
  for (size_t i = 0; i < t.columns.size(); ++i) out += "---|";
  out += '\n';
  for (const auto& row : t.rows) line(row);
  return out;
}

}  // namespace spume::report
