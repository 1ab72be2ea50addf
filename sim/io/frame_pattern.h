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
