#pragma once
// The whole comparison as `spume compare` runs it, for the command and for the golden-image tests:
// every frame compared, then with an output folder summary.csv, summary.json and report.html.
#include <functional>
#include <vector>

#include "render/app/compare/frame_compare.h"

namespace spume::compare {

// Writes the outputs when options.out is set; png files left in its thumbs/ and diff/ folders by
// an earlier comparison and not written now are removed (the folders are the report's own).
std::vector<FrameResult> compare_and_report(const FrameSet& set, const CompareOptions& options,
                                            const std::function<void(size_t)>& progress = {});

}  // namespace spume::compare
