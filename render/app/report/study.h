#pragma once
// What every study of `spume report` gets and gives back. A study measures error against a
// reference independent of the method it times, and returns its table, its plot and one paragraph of
// reading whose numbers come from the measurements.
#include <filesystem>
#include <functional>
#include <string>

#include "render/app/report/gnuplot_figure.h"
#include "render/app/report/report_table.h"

namespace spume::report {

struct StudyContext {
  std::filesystem::path scene_path;  // the scene file (render and diffuse studies)
  std::filesystem::path out_root;    // OUT: scene caches under OUT/<scene>, the report under OUT/report
  std::filesystem::path exe_dir;     // where the spume binary lives (the stability suite sits beside it)
  bool quick = false;
  bool quiet = false;
  // A progress line on stderr (nothing when quiet).
  std::function<void(const std::string&)> progress;
};

struct StudyResult {
  std::string key;       // file stem: OUT/report/<key>.csv, <key>.png
  std::string title;     // section heading
  std::string measures;  // one sentence: what is varied, what is measured, against what
  Table table;
  Figure figure;
  std::string reading;   // the paragraph, numbers computed
  double seconds = 0.0;  // wall clock of the study
};

StudyResult study_render(const StudyContext& context);
StudyResult study_diffuse(const StudyContext& context);
StudyResult study_fluid(const StudyContext& context);
StudyResult study_surface(const StudyContext& context);
StudyResult study_stability(const StudyContext& context);

}  // namespace spume::report
