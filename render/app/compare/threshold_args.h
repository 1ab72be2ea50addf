#pragma once
// The threshold options of `spume compare` as typed. Levels are whole 8-bit levels, "N" or "N/255"
// (idiff takes fractions of full range instead; a fraction below 1 is refused with the level it
// means, so a habit from idiff cannot silently mean something else). Percentages are plain
// decimals, optionally with a trailing '%', held exactly.
#include <string>

#include "render/image/image_compare.h"

namespace spume::compare {

// Throws UsageError naming `option`, the text and what is allowed.
int parse_level(const std::string& text, const std::string& option);
DecimalPercent parse_percent(const std::string& text, const std::string& option);

}  // namespace spume::compare
