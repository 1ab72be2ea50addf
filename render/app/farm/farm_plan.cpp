#include "render/app/farm/farm_plan.h"

#include <algorithm>

#include "sim/core/error.h"
#include "sim/core/frame_spec.h"

namespace spume::farm {

std::string format_frame_spec(const std::vector<int>& frames) {
  std::string spec;
  size_t i = 0;
  while (i < frames.size()) {
    if (!spec.empty()) spec += ',';
    // The longest evenly stepped run from frames[i].
    size_t j = i;
    if (i + 1 < frames.size()) {
      const int step = frames[i + 1] - frames[i];
      j = i + 1;
      while (j + 1 < frames.size() && frames[j + 1] - frames[j] == step) ++j;
      // Two frames far apart read better as a list; a stepped pair would need its own step.
      if (step != 1 && j == i + 1) j = i;
      if (j > i) spec += str(frames[i], "-", frames[j], step == 1 ? std::string() : str(":", step));
    }
    if (j == i) spec += std::to_string(frames[i]);
    i = j + 1;
  }
  return spec;
}

std::vector<int> select_frames(const std::string& spec, const std::vector<int>& available) {
  if (available.empty()) fail("--frames: the scene has no frames to render");
  std::vector<int> chosen;
  for (int f : parse_frame_spec(spec, available.front(), available.back(), "--frames"))
    if (std::binary_search(available.begin(), available.end(), f)) chosen.push_back(f);
  if (chosen.empty()) fail("--frames: \"", spec, "\" selects none of the scene's frames");
  return chosen;
}

std::vector<std::string> chunk_specs(const std::vector<int>& frames, int chunk) {
  if (chunk < 1) fail("--chunk: ", chunk, " is not a chunk size; give a whole number of frames from 1");
  std::vector<std::string> chunks;
  for (size_t i = 0; i < frames.size(); i += size_t(chunk)) {
    const size_t end = std::min(frames.size(), i + size_t(chunk));
    chunks.push_back(format_frame_spec(std::vector<int>(frames.begin() + long(i), frames.begin() + long(end))));
  }
  return chunks;
}

}  // namespace spume::farm
