#pragma once
// Writes OUT/report/: <key>.csv, <key>.png (and the <key>.gp that drew it) per study, and report.md
// with every table, plot and reading. Each file is written atomically.
#include <filesystem>
#include <string>
#include <vector>

#include "render/app/report/study.h"

namespace spume::report {

struct ReportHeader {
  std::string scene;       // scene file
  bool quick = false;
  int threads = 0;
  double seconds = 0.0;    // all studies
  std::string command;     // as typed
};

// The markdown text of the report (links are relative to the report folder).
std::string report_markdown(const ReportHeader& header, const std::vector<StudyResult>& studies);

// The study's CSV and PNG (+ .gp) into `dir`.
void write_study_files(const StudyResult& study, const std::filesystem::path& dir);
void write_report_markdown(const ReportHeader& header, const std::vector<StudyResult>& studies,
                           const std::filesystem::path& dir);

}  // namespace spume::report
