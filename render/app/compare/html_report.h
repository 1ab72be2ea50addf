#pragma once
// report.html: one self-contained page (inline CSS, script and SVG; nothing fetched from a network)
// for people. The verdict and thresholds, the plot of the error over the sequence, a viewer that
// shows a frame's reference and new image with a slider or a flip, its difference and heat map, and
// a table of every frame worst first with its numbers and lazily loaded thumbnails. Images are
// linked by relative paths: the thumbnails and difference images in the report folder, the frames
// where they are. Without scripts the header, plot and table are complete.
#include <filesystem>
#include <string>

#include "render/app/compare/summary_files.h"

namespace spume::compare {

// `dir` is the folder the page is written to (links are relative to it).
std::string report_html(const CompareReport& report, const std::filesystem::path& dir);
void write_report_html(const CompareReport& report, const std::filesystem::path& dir);

}  // namespace spume::compare
