#include "render/app/compare/frame_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <tuple>

#include "sim/core/parallel.h"
#include "render/image/difference_maps.h"
#include "render/image/png_io.h"
#include "render/image/thumbnail.h"

namespace spume::compare {
namespace fs = std::filesystem;
namespace {

struct Loaded {
  std::optional<ImageRGB8> image;
  std::string error;
};

Loaded load(const fs::path& path) {
  Loaded l;
  try {
    l.image = read_png(path);
  } catch (const Error& e) {
    l.error = e.what();
  }
  return l;
}

std::string levels(int n) { return str(n, "/255"); }

std::string percent(double p) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f%%", p);
  return buf;
}

std::string threshold_reason(const FrameResult& r, const CompareThresholds& t) {
  std::string reason;
  if (r.verdict.over_failpercent)
    reason = str(percent(r.stats.over_fail_percent()), " of pixels (", r.stats.over_fail, ") differ by more than ",
                 levels(t.fail), ", over the allowed ", t.failpercent.text(), "%");
  if (r.verdict.over_hardfail)
    reason += str(reason.empty() ? "" : "; ", "largest difference ", levels(r.stats.max_diff), " is over the hard limit ",
                  levels(t.hardfail), " (", r.stats.over_hardfail, " pixel", r.stats.over_hardfail == 1 ? "" : "s", ")");
  return reason;
}

void write_images(FrameResult& r, const ImageRGB8* ref, const ImageRGB8* cand, const CompareOptions& o) {
  const fs::path& out = *o.out;
  const std::string& stem = r.pair.stem;
  auto put = [&](const std::string& rel, const ImageRGB8& image) {
    write_png(out / rel, image);
    return rel;
  };
  if (ref) r.thumb_reference = put("thumbs/" + stem + "_reference.png", thumbnail(*ref, o.thumb_width));
  if (cand) r.thumb_candidate = put("thumbs/" + stem + "_new.png", thumbnail(*cand, o.thumb_width));
  if (r.compared && !r.passed()) {
    r.diff_image = put("diff/" + stem + "_diff.png", scaled_difference(*ref, *cand, o.diff_scale));
    r.heat_image = put("diff/" + stem + "_heat.png", difference_heat_map(*ref, *cand));
    r.thumb_heat = put("thumbs/" + stem + "_heat.png", difference_heat_thumbnail(*ref, *cand, o.thumb_width));
  }
}

FrameResult compare_one(const FramePair& pair, size_t index, const CompareOptions& o) {
  FrameResult r;
  r.pair = pair, r.index = index;
  Loaded ref, cand;
  if (pair.has_reference) ref = load(pair.reference);
  if (pair.has_candidate) cand = load(pair.candidate);
  if (ref.image) r.reference_width = ref.image->width, r.reference_height = ref.image->height;
  if (cand.image) r.candidate_width = cand.image->width, r.candidate_height = cand.image->height;

  if (!pair.has_reference || !pair.has_candidate) {
    r.status = Status::missing;
    if (!pair.has_reference && !pair.has_candidate)
      r.reason = str("missing in both: no ", pair.reference.string(), " and no ", pair.candidate.string());
    else if (!pair.has_reference)
      r.reason = str("missing in reference: no ", pair.reference.string());
    else
      r.reason = str("missing in new: no ", pair.candidate.string());
  } else if (!ref.image || !cand.image) {
    r.status = Status::unreadable;
    if (!ref.image) r.reason = "unreadable reference: " + ref.error;
    if (!cand.image) r.reason += str(r.reason.empty() ? "" : "; ", "unreadable new: ", cand.error);
  } else if (ref.image->width != cand.image->width || ref.image->height != cand.image->height) {
    r.status = Status::size_mismatch;
    r.reason = str("size mismatch: reference ", ref.image->width, "x", ref.image->height, " (", pair.reference.string(),
                   "), new ", cand.image->width, "x", cand.image->height, " (", pair.candidate.string(), ")");
  } else {
    r.compared = true;
    r.stats = compare_pixels(*ref.image, *cand.image, o.thresholds);
    // Most frames of a regression run are identical; their SSIM is known exactly.
    r.ssim = r.stats.identical() ? ssim_of_identical(ref.image->width, ref.image->height)
                                 : ssim_rgb(*ref.image, *cand.image);
    r.verdict = judge(r.stats, o.thresholds);
    r.status = !r.verdict.pass() ? Status::fail : r.stats.identical() ? Status::identical : Status::pass;
    if (!r.verdict.pass()) r.reason = threshold_reason(r, o.thresholds);
  }
  if (o.out) write_images(r, ref.image ? &*ref.image : nullptr, cand.image ? &*cand.image : nullptr, o);
  return r;
}

}  // namespace

const char* status_code(Status s) {
  switch (s) {
    case Status::unreadable: return "unreadable";
    case Status::missing: return "missing";
    case Status::size_mismatch: return "size-mismatch";
    case Status::fail: return "fail";
    case Status::pass: return "pass";
    case Status::identical: return "identical";
  }
  return "?";
}

std::vector<FrameResult> compare_frames(const FrameSet& set, const CompareOptions& o,
                                        const std::function<void(size_t)>& progress) {
  if (o.diff_scale < 1) fail("difference scale ", o.diff_scale, " must be at least 1");
  std::vector<FrameResult> results(set.frames.size());
  std::mutex progress_mutex;
  size_t done = 0;
  // One frame per task: each frame decodes two images and measures them on its own.
  parallel_for(set.frames.size(), 1, [&](size_t b, size_t e) {
    for (size_t i = b; i < e; ++i) {
      results[i] = compare_one(set.frames[i], i, o);
      if (progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        progress(++done);
      }
    }
  });
  return results;
}

std::vector<size_t> worst_first(const std::vector<FrameResult>& results) {
  std::vector<size_t> order(results.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto key = [&](size_t i) {
    const FrameResult& r = results[i];
    // Larger is worse for every element after the status rank, so they are negated.
    return std::make_tuple(int(r.status), -double(r.stats.over_fail) / double(std::max<size_t>(r.stats.pixels, 1)),
                           -r.stats.max_diff, -int64_t(r.stats.sum_abs), r.index);
  };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return key(a) < key(b); });
  return order;
}

Overall summarize(const std::vector<FrameResult>& results) {
  Overall o;
  o.frames = results.size();
  o.min_psnr_db = std::numeric_limits<double>::infinity();
  size_t compared = 0;
  double mean_sum = 0.0;
  for (const FrameResult& r : results) {
    if (r.passed()) ++o.passed;
    else ++o.failed;
    switch (r.status) {
      case Status::identical: ++o.identical; break;
      case Status::missing: ++o.missing; break;
      case Status::size_mismatch: ++o.size_mismatch; break;
      case Status::unreadable: ++o.unreadable; break;
      case Status::fail: ++o.over_thresholds; break;
      case Status::pass: break;
    }
    if (!r.compared) continue;
    ++compared;
    o.max_diff = std::max(o.max_diff, r.stats.max_diff);
    o.max_over_fail_percent = std::max(o.max_over_fail_percent, r.stats.over_fail_percent());
    mean_sum += r.stats.mean_diff();
    o.min_psnr_db = std::min(o.min_psnr_db, r.stats.psnr_db());
    if (r.ssim.defined) o.min_ssim = std::min(o.min_ssim.value_or(1.0), r.ssim.mean);
  }
  if (compared) o.mean_diff = mean_sum / double(compared);
  for (size_t i : worst_first(results))
    if (results[i].compared) {
      o.worst = i;
      break;
    }
  return o;
}

}  // namespace spume::compare
