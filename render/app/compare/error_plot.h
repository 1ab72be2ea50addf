#pragma once
// The report's plot of the error over the sequence, as inline SVG (no scripts, no external files):
// the share of pixels over --fail (log scale) and the largest difference (on the heat map's
// log2(1 + level) scale), each with its threshold dashed; failing frames in red, frames that could
// not be compared marked at the top. Every point carries its frame index (data-index) and a tooltip.
#include <string>
#include <vector>

#include "render/app/compare/frame_compare.h"

namespace spume::compare {

std::string error_plot_svg(const std::vector<FrameResult>& results, const CompareThresholds& thresholds);

}  // namespace spume::compare
