#include "render/app/report/report_writer.h"

#include "sim/core/atomic_file.h"

namespace spume::report {

std::string report_markdown(const ReportHeader& h, const std::vector<StudyResult>& studies) {
  std::string md = "# spume report: error against run time, and stability\n\n";
  md += "Scene `" + h.scene + "`" + (h.quick ? ", `--quick`" : "") + ", " + std::to_string(h.threads) +
        " threads; all studies took " + num(h.seconds, 3) + " s. Command: `" + h.command + "`.\n\n";
  md += "Every error is measured against a reference that does not use the method being timed.\n\n";
  for (const StudyResult& s : studies) {
    md += "## " + s.title + "\n\n" + s.measures + " (" + num(s.seconds, 3) + " s; data: [" + s.key + ".csv](" +
          s.key + ".csv))\n\n";
    if (!s.figure.panels.empty()) md += "![" + s.title + "](" + s.key + ".png)\n\n";
    md += to_markdown(s.table) + "\n" + s.reading + "\n\n";
  }
  return md;
}

void write_study_files(const StudyResult& s, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  write_file_atomically(dir / (s.key + ".csv"), [&](std::ostream& out) { out << to_csv(s.table); });
  if (!s.figure.panels.empty()) draw_figure(s.figure, dir / (s.key + ".png"), dir / (s.key + ".gp"));
}

void write_report_markdown(const ReportHeader& h, const std::vector<StudyResult>& studies,
                           const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  write_file_atomically(dir / "report.md", [&](std::ostream& out) { out << report_markdown(h, studies); });
}

}  // namespace spume::report
