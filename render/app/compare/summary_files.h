#pragma once
// The comparison for scripts: summary.csv (one row per frame in sequence order, then an "overall"
// row) and summary.json (thresholds, metric definitions, overall figures, then every frame).
#include <filesystem>
#include <string>
#include <vector>

#include "render/app/compare/frame_compare.h"

namespace spume::compare {

struct CompareReport {
  const FrameSet& set;
  const std::vector<FrameResult>& results;
  const CompareOptions& options;
};

std::string summary_csv(const CompareReport& report);
std::string summary_json(const CompareReport& report);

// Both files into `dir`, each written atomically.
void write_summary_files(const CompareReport& report, const std::filesystem::path& dir);

// One-line descriptions shared by the files and the HTML report.
extern const char* const kDifferenceDefinition;
extern const char* const kPsnrDefinition;
extern const char* const kSsimDefinition;

std::string format_fixed(double value, int decimals);  // "%.*f", "inf" for +infinity
std::string mode_name(FrameSet::Mode mode);

}  // namespace spume::compare
