#pragma once
// Splitting the frames of a render into chunks for a farm (one Slurm array task or one GNU parallel
// job per chunk), each chunk written as a frame spec that `spume render --frames` takes back.
#include <string>
#include <vector>

namespace spume::farm {

// Sorted, unique frames as a compact spec: runs of consecutive frames as A-B, evenly stepped runs
// of 3 or more as A-B:STEP, other frames alone, comma-separated ("0-9", "0-18:2", "1-3,5,10-20").
// parse_frame_spec(format_frame_spec(f), ...) gives f back.
std::string format_frame_spec(const std::vector<int>& frames);

// The frames of `spec` among `available` (sorted), clamped to its range as `spume render --frames`
// clamps them. Throws Error naming --frames when the spec is malformed or selects none.
std::vector<int> select_frames(const std::string& spec, const std::vector<int>& available);

// Consecutive groups of `chunk` frames (the last one may be shorter), each as a frame spec.
// Throws Error naming --chunk when chunk < 1.
std::vector<std::string> chunk_specs(const std::vector<int>& frames, int chunk);

}  // namespace spume::farm
