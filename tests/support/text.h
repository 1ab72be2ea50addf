#pragma once
// Text checks for what a command printed or a file holds.
#include <string>

namespace spume::testing {

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace spume::testing
