#include "sim/stage/diffuse_stats_csv.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <utility>

#include "sim/core/atomic_file.h"

namespace spume {
namespace {

std::string header() {
  std::string h = "frame,time,fluid,spray,foam,bubbles,generated,dissolved,removed,landed,dropped,capped";
  for (const char* stage : kStageNames) h += std::string(",") + stage + "_ms";
  return h + ",io_ms\n";
}

// The rows of an earlier file for frames up to `last`, header included ("" when unreadable or of
// another column layout).
std::string rows_up_to(const std::filesystem::path& path, int last) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line) || line + '\n' != header()) return "";
  std::string kept = line + '\n';
  while (std::getline(in, line))
    if (std::atoi(line.c_str()) <= last) kept += line + '\n';
  return kept;
}

}  // namespace

DiffuseStatsCsv::DiffuseStatsCsv(std::filesystem::path path, std::optional<int> continued_from)
    : path_(std::move(path)) {
  if (continued_from) text_ = rows_up_to(path_, *continued_from);
  if (text_.empty()) text_ = header();
}

void DiffuseStatsCsv::add(const FrameStats& s, double time, double io_ms) {
  std::ostringstream out;
  out << s.frame << ',' << time << ',' << s.fluid << ',' << s.by_type[0] << ',' << s.by_type[1] << ','
      << s.by_type[2] << ',' << s.generated << ',' << s.dissolved << ',' << s.removed << ',' << s.landed << ',' << s.dropped << ',' << s.capped;
  char buffer[32];
  for (double ms : s.stage_ms) std::snprintf(buffer, sizeof buffer, ",%.2f", ms), out << buffer;
  std::snprintf(buffer, sizeof buffer, ",%.2f\n", io_ms);
  out << buffer;
  text_ += out.str();
}

void DiffuseStatsCsv::write() const {
  write_file_atomically(path_, [&](std::ostream& out) { out << text_; });
}

}  // namespace spume
