#pragma once
// File-name patterns for frame sequences: "fluid_%04d.bgeo", "fluid_%d.vtk", "fluid_####.bgeo".
//   %d     the frame number without padding
//   %0Nd   zero-padded to at least N digits (N = 1..20)
//   #...#  a run of N hashes: zero-padded to at least N digits
//   $F     Houdini's frame variable: no padding; $FN (N = 1..9) zero-padded to at least N digits
//   %%     a literal '%'
// A pattern holds exactly one placeholder; any other '%' sequence is an error.
#include <string>
#include <vector>

namespace spume {

// How a pattern writes its placeholder: %d / %0Nd, a run of '#', or Houdini's $F / $FN.
enum class PlaceholderStyle { Printf, Hashes, Houdini };

// A pattern split around its single placeholder ("%%" already turned into '%').
struct FramePatternParts {
  std::string prefix, suffix;
  int width = 0;  // minimum digits; 0 means no padding (a width of 1 is reported as 0: the same names)
  PlaceholderStyle style = PlaceholderStyle::Printf;
};

// Throws Error for a malformed pattern, as expand_frame_pattern does.
FramePatternParts parse_frame_pattern(const std::string& pattern);

// The pattern of `parts` written in `parts.style` when that style can say it (Houdini's $FN stops at
// 9 digits; a '#' or "$F" in the text would read as a second placeholder), else in printf style;
// "" when no style can ('#' or "$F" in the text). Parsing the result gives `parts` back.
std::string compose_frame_pattern(const FramePatternParts& parts);

// The same files however the pattern was typed, for comparing inputs: the folder made absolute with
// symbolic links resolved, the placeholder in printf style (%d, %0Nd). A malformed pattern comes back
// as it is (reading the files says what is wrong).
std::string canonical_frame_pattern(const std::string& pattern);

// True when the string contains a frame placeholder (it may still be malformed; expand reports that).
bool is_frame_pattern(const std::string& pattern);

// The file name of `frame` (>= 0). Throws Error for a malformed pattern or a negative frame.
std::string expand_frame_pattern(const std::string& pattern, int frame);

// Sorted frame numbers of the existing files matching the pattern. The placeholder must be in the
// file-name part. A file matches when its name is exactly what expand_frame_pattern gives for its
// number: "%d" takes any number of digits (no leading zeros), "%04d" at least 4 digits.
// Throws Error when the directory does not exist.
std::vector<int> find_pattern_frames(const std::string& pattern);

}  // namespace spume
