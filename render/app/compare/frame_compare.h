#pragma once
// `spume compare`'s work per frame: read both PNGs, judge them against the thresholds, measure them,
// and (with an output folder) write the frame's thumbnails and, when it fails, its difference
// images. Frames run in parallel; each frame's figures are computed by one task, so results do not
// depend on the thread count.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "render/app/compare/frame_set.h"
#include "render/image/image_compare.h"
#include "render/image/ssim.h"

namespace spume::compare {

struct CompareOptions {
  CompareThresholds thresholds = regression_thresholds();
  int diff_scale = 16;                       // the difference image shows |reference - new| x this
  std::optional<std::filesystem::path> out;  // thumbnails and difference images go here
  int thumb_width = 240;
};

// Failures that are not about pixels come first in the enum's order of severity for sorting.
enum class Status { unreadable, missing, size_mismatch, fail, pass, identical };
const char* status_code(Status status);  // "unreadable", "missing", "size-mismatch", "fail", "pass", "identical"

struct FrameResult {
  FramePair pair;
  size_t index = 0;  // position in the sequence
  Status status = Status::missing;
  std::string reason;  // why it failed, in words naming the file or the figure and its limit; empty for passes
  int reference_width = 0, reference_height = 0, candidate_width = 0, candidate_height = 0;  // 0: not read
  bool compared = false;  // the pixel figures below are valid
  PixelStats stats;
  SsimResult ssim;
  ThresholdVerdict verdict;
  // Files written for this frame, relative to the output folder; empty when not written.
  std::string thumb_reference, thumb_candidate, thumb_heat, diff_image, heat_image;

  bool passed() const { return status == Status::pass || status == Status::identical; }
};

// One result per frame of the set, in the set's order. `progress(done)` is called (serialised) as
// frames finish. Throws Error only when an output file cannot be written.
std::vector<FrameResult> compare_frames(const FrameSet& frames, const CompareOptions& options,
                                        const std::function<void(size_t)>& progress = {});

// Indices of `results`, worst first: failures before passes; among failures, frames that could not
// be compared (unreadable, missing, other size) first; then by share of pixels over --fail, largest
// difference, mean difference, each descending; ties in sequence order.
std::vector<size_t> worst_first(const std::vector<FrameResult>& results);

struct Overall {
  size_t frames = 0, passed = 0, failed = 0, identical = 0;
  size_t missing = 0, size_mismatch = 0, unreadable = 0, over_thresholds = 0;
  std::optional<size_t> worst;  // index of the worst frame that was compared, if any
  int max_diff = 0;             // over compared frames
  double max_over_fail_percent = 0.0, mean_diff = 0.0;  // mean over compared frames' means
  double min_psnr_db = 0.0;     // +inf when every compared frame is identical
  std::optional<double> min_ssim;
  bool pass() const { return failed == 0; }
};
Overall summarize(const std::vector<FrameResult>& results);

}  // namespace spume::compare
