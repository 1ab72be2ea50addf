#pragma once
// What to tell a user whose frame pattern matches no file: the usual slip is the padding ($F for
// files named f_0001, $F4 for f_1), or a name that differs from the files' by a letter or a case.
#include <string>

namespace spume {

// A sentence (starting with "; ") naming a pattern that does match files in the pattern's folder,
// in the pattern's own placeholder style, with how many files and which frames; or, when the folder
// holds no numbered files, what it does hold. "" when the folder cannot be listed.
std::string unmatched_pattern_hint(const std::string& pattern);

}  // namespace spume
