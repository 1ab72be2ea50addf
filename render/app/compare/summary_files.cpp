#include "render/app/compare/summary_files.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "sim/core/atomic_file.h"

namespace spume::compare {

const char* const kDifferenceDefinition =
    "a pixel's difference is its largest channel difference in 8-bit levels (1 = 1/255 of full range)";
const char* const kPsnrDefinition = "PSNR = 10 log10(255^2 / MSE) dB, MSE over every channel of every pixel";
const char* const kSsimDefinition =
    "SSIM of Wang, Bovik, Sheikh and Simoncelli (IEEE TIP 2004): 11x11 Gaussian window, sigma 1.5, "
    "K1 = 0.01, K2 = 0.03, L = 255, every window inside the image, per R, G, B channel, mean of the three";

std::string format_fixed(double value, int decimals) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

std::string mode_name(FrameSet::Mode mode) {
  switch (mode) {
    case FrameSet::Mode::files: return "files";
    case FrameSet::Mode::folders: return "folders";
    case FrameSet::Mode::patterns: return "patterns";
  }
  return "?";
}

namespace {

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

void append_row(std::string& out, const std::vector<std::string>& cells) {
  for (size_t k = 0; k < cells.size(); ++k) {
    if (k) out += ',';
    out += csv_field(cells[k]);
  }
  out += '\n';
}

std::vector<size_t> ranks(const std::vector<FrameResult>& results) {
  std::vector<size_t> rank(results.size());
  const std::vector<size_t> order = worst_first(results);
  for (size_t k = 0; k < order.size(); ++k) rank[order[k]] = k + 1;
  return rank;
}

}  // namespace

std::string summary_csv(const CompareReport& rep) {
  std::string out =
      "frame,number,rank,status,reason,reference,new,width,height,pixels,over_fail,over_fail_percent,over_hardfail,"
      "max_diff,mean_diff,rmse,psnr_db,ssim,ssim_r,ssim_g,ssim_b,diff_image,heat_image\n";
  const std::vector<size_t> rank = ranks(rep.results);
  for (const FrameResult& r : rep.results) {
    std::vector<std::string> f = {r.pair.label, r.pair.number ? std::to_string(*r.pair.number) : "",
                                  std::to_string(rank[r.index]), status_code(r.status), r.reason,
                                  r.pair.reference.string(), r.pair.candidate.string()};
    if (r.compared) {
      const PixelStats& s = r.stats;
      f.insert(f.end(), {std::to_string(r.reference_width), std::to_string(r.reference_height), std::to_string(s.pixels),
                         std::to_string(s.over_fail), format_fixed(s.over_fail_percent(), 6),
                         std::to_string(s.over_hardfail), std::to_string(s.max_diff), format_fixed(s.mean_diff(), 6),
                         format_fixed(s.rmse(), 6), format_fixed(s.psnr_db(), 4)});
      if (r.ssim.defined)
        f.insert(f.end(), {format_fixed(r.ssim.mean, 6), format_fixed(r.ssim.channel[0], 6),
                           format_fixed(r.ssim.channel[1], 6), format_fixed(r.ssim.channel[2], 6)});
      else
        f.insert(f.end(), 4, "");
    } else {
      f.insert(f.end(), 14, "");
    }
    f.push_back(r.diff_image), f.push_back(r.heat_image);
    append_row(out, f);
  }
  // The overall row: counts summed, the worst of every figure (largest share, difference and
  // mean, smallest PSNR and SSIM).
  const Overall o = summarize(rep.results);
  size_t pixels = 0, over_fail = 0, over_hard = 0;
  for (const FrameResult& r : rep.results)
    if (r.compared) pixels += r.stats.pixels, over_fail += r.stats.over_fail, over_hard += r.stats.over_hardfail;
  const bool any = o.frames > o.missing + o.size_mismatch + o.unreadable;
  std::vector<std::string> f = {"overall", "", "", o.pass() ? "pass" : "fail",
                                str(o.failed, " of ", o.frames, " frames fail"), rep.set.reference_source,
                                rep.set.candidate_source, "", "", std::to_string(pixels), std::to_string(over_fail),
                                any ? format_fixed(o.max_over_fail_percent, 6) : "", std::to_string(over_hard),
                                any ? std::to_string(o.max_diff) : "", any ? format_fixed(o.mean_diff, 6) : "", "",
                                any ? format_fixed(o.min_psnr_db, 4) : "",
                                o.min_ssim ? format_fixed(*o.min_ssim, 6) : "", "", "", "", "", ""};
  append_row(out, f);
  return out;
}

std::string summary_json(const CompareReport& rep) {
  using nlohmann::ordered_json;
  const CompareThresholds& t = rep.options.thresholds;
  const Overall o = summarize(rep.results);
  const std::vector<size_t> rank = ranks(rep.results);
  auto number_or_null = [](double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); };
  ordered_json j;
  j["tool"] = "spume compare";
  j["reference"] = rep.set.reference_source;
  j["new"] = rep.set.candidate_source;
  j["mode"] = mode_name(rep.set.mode);
  j["thresholds"] = {{"fail", t.fail}, {"failpercent", t.failpercent.value()}, {"hardfail", t.hardfail},
                     {"units", "fail and hardfail in 8-bit levels (1 = 1/255); failpercent in percent of pixels"}};
  j["definitions"] = {{"difference", kDifferenceDefinition},
                      {"psnr_db", std::string(kPsnrDefinition) + "; null when the images are identical (infinite)"},
                      {"ssim", kSsimDefinition},
                      {"rank", "1 = worst: failures first (unreadable, missing, size mismatch, then over the "
                               "thresholds), then by share over fail, max and mean difference"}};
  ordered_json overall = {{"verdict", o.pass() ? "pass" : "fail"},
                          {"frames", o.frames},
                          {"passed", o.passed},
                          {"failed", o.failed},
                          {"identical", o.identical},
                          {"over_thresholds", o.over_thresholds},
                          {"missing", o.missing},
                          {"size_mismatch", o.size_mismatch},
                          {"unreadable", o.unreadable}};
  overall["worst_frame"] = o.worst ? ordered_json(rep.results[*o.worst].pair.label) : ordered_json(nullptr);
  const bool any = o.frames > o.missing + o.size_mismatch + o.unreadable;
  overall["max_over_fail_percent"] = any ? ordered_json(o.max_over_fail_percent) : ordered_json(nullptr);
  overall["max_diff"] = any ? ordered_json(o.max_diff) : ordered_json(nullptr);
  overall["mean_diff"] = any ? ordered_json(o.mean_diff) : ordered_json(nullptr);
  overall["min_psnr_db"] = any ? number_or_null(o.min_psnr_db) : ordered_json(nullptr);
  overall["min_ssim"] = o.min_ssim ? ordered_json(*o.min_ssim) : ordered_json(nullptr);
  j["overall"] = overall;
  ordered_json frames = ordered_json::array();
  for (const FrameResult& r : rep.results) {
    ordered_json f;
    f["frame"] = r.pair.label;
    f["number"] = r.pair.number ? ordered_json(*r.pair.number) : ordered_json(nullptr);
    f["rank"] = rank[r.index];
    f["status"] = status_code(r.status);
    f["pass"] = r.passed();
    f["reason"] = r.reason;
    f["reference"] = r.pair.reference.string();
    f["new"] = r.pair.candidate.string();
    if (r.reference_width) f["reference_size"] = {r.reference_width, r.reference_height};
    if (r.candidate_width) f["new_size"] = {r.candidate_width, r.candidate_height};
    if (r.compared) {
      const PixelStats& s = r.stats;
      f["pixels"] = s.pixels;
      f["over_fail"] = s.over_fail;
      f["over_fail_percent"] = s.over_fail_percent();
      f["over_hardfail"] = s.over_hardfail;
      f["max_diff"] = s.max_diff;
      f["mean_diff"] = s.mean_diff();
      f["rmse"] = s.rmse();
      f["psnr_db"] = number_or_null(s.psnr_db());
      f["ssim"] = r.ssim.defined ? ordered_json(r.ssim.mean) : ordered_json(nullptr);
      f["ssim_rgb"] = r.ssim.defined ? ordered_json(r.ssim.channel) : ordered_json(nullptr);
    }
    f["diff_image"] = r.diff_image.empty() ? ordered_json(nullptr) : ordered_json(r.diff_image);
    f["heat_image"] = r.heat_image.empty() ? ordered_json(nullptr) : ordered_json(r.heat_image);
    frames.push_back(f);
  }
  j["frames"] = frames;
  // Paths are bytes on Linux: invalid UTF-8 is replaced rather than refused.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

void write_summary_files(const CompareReport& rep, const std::filesystem::path& dir) {
  const std::string csv = summary_csv(rep), json = summary_json(rep);
  write_file_atomically(dir / "summary.csv", [&](std::ostream& out) { out << csv; });
  write_file_atomically(dir / "summary.json", [&](std::ostream& out) { out << json; });
}

}  // namespace spume::compare
