#pragma once
// Frame specs as users type them wherever a set of frames is taken (--frames, farm chunks):
//   7            one frame
//   0-99         frames 0 to 99, both included
//   0-99:2       every 2nd frame from 0: 0, 2, ..., 98
//   1-3,5,10-20  any comma-separated list of the above
// Frames are non-negative integers; no spaces, signs or empty items.
#include <string_view>
#include <vector>

namespace spume {

// The frames of `spec` that lie in [first, last], sorted, without repeats. Items are clipped to the
// range, so a farm chunk that overshoots the last frame selects what remains; a stepped range keeps
// its phase from its own start (0-99:2 clipped to [1, 99] gives 2, 4, ..., 98). Throws Error naming
// `what` (the option or key, e.g. "--frames"), the spec and the accepted forms when the spec is
// malformed, a range is reversed (5-3), a step is 0, a number does not fit an int, first > last, or
// nothing of the spec lies in [first, last].
std::vector<int> parse_frame_spec(std::string_view spec, int first, int last, const char* what);

}  // namespace spume
