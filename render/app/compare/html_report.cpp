#include "render/app/compare/html_report.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "sim/core/atomic_file.h"
#include "render/app/compare/error_plot.h"
#include "render/app/compare/html_assets.h"
#include "render/app/compare/html_text.h"
#include "render/image/difference_maps.h"
#include "render/image/thumbnail.h"

namespace spume::compare {
namespace fs = std::filesystem;
namespace {

std::string verdict_word(Status s) {
  switch (s) {
    case Status::identical: return "identical";
    case Status::pass: return "pass";
    case Status::fail: return "FAIL";
    case Status::missing: return "missing";
    case Status::size_mismatch: return "size mismatch";
    case Status::unreadable: return "unreadable";
  }
  return "?";
}

std::string plural(size_t n, const char* one, const char* many) { return str(n, " ", n == 1 ? one : many); }

std::string counts_sentence(const Overall& o) {
  if (o.frames == 0) return "No frames.";
  const size_t within = o.passed - o.identical;
  if (o.pass())
    return str(o.frames == 1 ? "The frame passes" : str("All ", o.frames, " frames pass"), ": ", o.identical,
               " identical, ", within, " within the thresholds.");
  std::string parts;
  auto add = [&](size_t n, const char* what) {
    if (n) parts += str(parts.empty() ? "" : ", ", n, " ", what);
  };
  add(o.over_thresholds, "over the thresholds");
  add(o.missing, "missing");
  add(o.size_mismatch, "of another size");
  add(o.unreadable, "unreadable");
  return str(o.failed, " of ", plural(o.frames, "frame", "frames"), o.failed == 1 ? " fails (" : " fail (", parts, "); ", o.identical,
             " identical, ", within, " pass within the thresholds.");
}

std::string psnr_text(const FrameResult& r) {
  return r.stats.identical() ? "&infin;" : format_fixed(r.stats.psnr_db(), 2);
}

// The viewer's data: one entry per frame in sequence order.
std::string frame_data_json(const CompareReport& rep, const fs::path& dir) {
  using nlohmann::ordered_json;
  ordered_json frames = ordered_json::array();
  for (const FrameResult& r : rep.results) {
    ordered_json f;
    f["i"] = r.index;
    f["label"] = r.pair.label;
    f["stem"] = r.pair.stem;
    f["status"] = status_code(r.status);
    f["verdict"] = verdict_word(r.status);
    f["pass"] = r.passed();
    f["reason"] = r.reason;
    const bool ref_ok = r.reference_width > 0, new_ok = r.candidate_width > 0;
    f["w"] = r.reference_width, f["h"] = r.reference_height;  // 0 when not decoded
    f["nw"] = r.candidate_width, f["nh"] = r.candidate_height;
    // Only images that decoded are linked: a browser cannot show the others either.
    f["ref"] = ref_ok ? ordered_json(relative_url(r.pair.reference, dir)) : ordered_json(nullptr);
    f["new"] = new_ok ? ordered_json(relative_url(r.pair.candidate, dir)) : ordered_json(nullptr);
    f["diff"] = r.diff_image.empty() ? ordered_json(nullptr) : ordered_json(url_path(r.diff_image));
    f["heat"] = r.heat_image.empty() ? ordered_json(nullptr) : ordered_json(url_path(r.heat_image));
    if (r.compared) {
      f["numbers"] = ordered_json::array(
          {ordered_json::array({str("pixels over ", rep.options.thresholds.fail, "/255"),
                                str(r.stats.over_fail, " (", format_fixed(r.stats.over_fail_percent(), 4), "%)")}),
           ordered_json::array({"largest difference", str(r.stats.max_diff, "/255")}),
           ordered_json::array({"mean difference", format_fixed(r.stats.mean_diff(), 4) + " levels"}),
           ordered_json::array({"RMSE", format_fixed(r.stats.rmse(), 4) + " levels"}),
           ordered_json::array({"PSNR", r.stats.identical() ? std::string("infinite (identical)")
                                                             : format_fixed(r.stats.psnr_db(), 3) + " dB"}),
           ordered_json::array({"SSIM (R, G, B)", r.ssim.defined ? str(format_fixed(r.ssim.mean, 5), " (",
                                                                        format_fixed(r.ssim.channel[0], 5), ", ",
                                                                        format_fixed(r.ssim.channel[1], 5), ", ",
                                                                        format_fixed(r.ssim.channel[2], 5), ")")
                                                                  : std::string("n/a (smaller than 11x11)")}),
           ordered_json::array({"size", str(r.reference_width, "x", r.reference_height)})});
    } else {
      f["numbers"] = ordered_json::array();
    }
    frames.push_back(f);
  }
  ordered_json j = {{"scale", rep.options.diff_scale}, {"frames", frames}};
  std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  // Inside <script>, "</" could end the element early; JSON allows the escaped form "<\/".
  for (size_t p = 0; (p = text.find("</", p)) != std::string::npos; p += 3) text.replace(p, 2, "<\\/");
  return text;
}

std::string thumb_cell(const std::string& rel, int w, int h, int max_w, const std::string& full, const std::string& alt,
                       const char* absent) {
  if (rel.empty()) return str("<td class=\"thumb none\">", absent, "</td>");
  const ThumbnailSize t = thumbnail_size(w, h, max_w);
  const std::string img = str("<img loading=\"lazy\" decoding=\"async\" src=\"", url_path(rel), "\" width=\"", t.width,
                              "\" height=\"", t.height, "\" alt=\"", html_escape(alt), "\">");
  return full.empty() ? str("<td class=\"thumb\">", img, "</td>")
                      : str("<td class=\"thumb\"><a href=\"", full, "\">", img, "</a></td>");
}

std::string table_row(const CompareReport& rep, const FrameResult& r, size_t rank, const fs::path& dir) {
  const char* cls = r.passed() ? "pass" : "fail";
  std::string row = str("<tr id=\"f-", r.pair.stem, "\" class=\"", cls, "\" data-index=\"",
                        r.index, "\" data-frame=\"", html_escape(r.pair.label), "\" data-verdict=\"",
                        status_code(r.status), "\" data-pass=\"", r.passed() ? 1 : 0, "\" data-rank=\"", rank,
                        "\" tabindex=\"0\">");
  row += str("<td class=\"num rank\">", rank, "</td><td class=\"name\"><a href=\"#f-", r.pair.stem, "\">",
             html_escape(r.pair.label), "</a></td>");
  row += str("<td class=\"verdict\"><span class=\"badge ", cls, "\">", verdict_word(r.status), "</span>");
  // Figures are in their columns; the row says only which limit they broke, or what went wrong.
  if (r.status == Status::fail) {
    const CompareThresholds& t = rep.options.thresholds;
    if (r.verdict.over_failpercent) row += str("<div class=\"reason\">over ", t.failpercent.text(), "% of pixels</div>");
    if (r.verdict.over_hardfail) row += str("<div class=\"reason\">max over ", t.hardfail, "/255</div>");
  } else if (!r.reason.empty()) {
    row += str("<div class=\"reason\">", html_escape(r.reason), "</div>");
  }
  row += "</td>";
  if (r.compared) {
    row += str("<td class=\"num\">", format_fixed(r.stats.over_fail_percent(), 4), "%</td><td class=\"num\">",
               r.stats.max_diff, "</td><td class=\"num\">", format_fixed(r.stats.mean_diff(), 3),
               "</td><td class=\"num\">", psnr_text(r), "</td><td class=\"num\">",
               r.ssim.defined ? format_fixed(r.ssim.mean, 5) : "n/a", "</td>");
  } else {
    row += "<td class=\"num\" colspan=\"5\">&ndash;</td>";
  }
  const int tw = rep.options.thumb_width;
  row += thumb_cell(r.thumb_reference, r.reference_width, r.reference_height, tw,
                    r.reference_width ? relative_url(r.pair.reference, dir) : "", "reference " + r.pair.label,
                    r.pair.has_reference ? "unreadable" : "missing");
  row += thumb_cell(r.thumb_candidate, r.candidate_width, r.candidate_height, tw,
                    r.candidate_width ? relative_url(r.pair.candidate, dir) : "", "new " + r.pair.label,
                    r.pair.has_candidate ? "unreadable" : "missing");
  row += thumb_cell(r.thumb_heat, r.reference_width, r.reference_height, tw, url_path(r.heat_image),
                    "heat map " + r.pair.label, r.passed() ? "" : "&ndash;");
  return row + "</tr>\n";
}

std::string heat_legend() {
  std::string s = "<span class=\"legend\">heat map: ";
  for (int level : {1, 3, 15, 63, 255}) {
    const Rgb8 c = heat_colour(level);
    char colour[8];
    std::snprintf(colour, sizeof colour, "#%02x%02x%02x", c.r, c.g, c.b);
    s += str("<span class=\"swatch\" style=\"background:", colour, "\"></span>", level, " ");
  }
  return s + "levels of 255 (a pixel's largest channel difference); unchanged pixels show the reference dimmed</span>";
}

}  // namespace

std::string report_html(const CompareReport& rep, const fs::path& dir) {
  const Overall o = summarize(rep.results);
  const CompareThresholds& t = rep.options.thresholds;
  const char* verdict = o.pass() ? "pass" : "fail";
  std::string h;
  h += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  h += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  h += str("<title>spume compare: ", o.pass() ? "PASS" : "FAIL", ", ", o.failed, " of ",
           plural(o.frames, "frame", "frames"), " fail</title>\n");
  h += str("<style>\n", kReportCss, "</style>\n</head>\n");
  h += str("<body data-status=\"loading\" data-verdict=\"", verdict, "\" data-frames=\"", o.frames, "\" data-failed=\"",
           o.failed, "\">\n");
  h += str("<header class=\"banner ", verdict, "\"><h1>spume compare <span class=\"overall\">", o.pass() ? "PASS" : "FAIL",
           "</span></h1><p id=\"counts\">", html_escape(counts_sentence(o)), "</p></header>\n");
  h += "<div id=\"script-error\" hidden></div>\n";

  h += "<section class=\"meta\"><table>\n";
  h += str("<tr><th>reference</th><td><code>", html_escape(rep.set.reference_source), "</code></td></tr>\n");
  h += str("<tr><th>new</th><td><code>", html_escape(rep.set.candidate_source), "</code></td></tr>\n");
  h += str("<tr><th>rule</th><td>a pixel fails when a channel differs by more than ", t.fail,
           "/255; a frame fails when more than ", t.failpercent.text(), "% of its pixels fail or any pixel differs by more than ",
           t.hardfail, "/255, and when it is missing, unreadable or of another size</td></tr>\n");
  if (o.worst) {
    const FrameResult& w = rep.results[*o.worst];
    h += str("<tr><th>worst compared</th><td><a href=\"#f-", w.pair.stem, "\">", html_escape(w.pair.label), "</a>: ",
             format_fixed(w.stats.over_fail_percent(), 4), "% of pixels over ", t.fail, "/255, largest difference ",
             w.stats.max_diff, "/255; over all compared frames: smallest PSNR ",
             std::isinf(o.min_psnr_db) ? std::string("&infin;") : format_fixed(o.min_psnr_db, 2) + " dB",
             ", smallest SSIM ", o.min_ssim ? format_fixed(*o.min_ssim, 5) : std::string("n/a"), "</td></tr>\n");
  }
  for (const std::string& note : rep.set.notes) h += str("<tr><th>note</th><td>", html_escape(note), "</td></tr>\n");
  h += "</table></section>\n";

  h += str("<section id=\"plot\"><h2>Error over the sequence</h2>\n", error_plot_svg(rep.results, t),
           "<p class=\"hint\">Click a point to view its frame.</p></section>\n");

  h += R"HTML(<section id="viewer" hidden>
<div class="viewer-head"><h2>Frame <span id="v-label"></span> <span id="v-verdict" class="badge"></span></h2>
<div class="v-nav"><button type="button" id="v-prev" title="previous row (k)">&#9664; previous</button><button type="button" id="v-next" title="next row (j)">next &#9654;</button></div></div>
<div class="v-modes"><button type="button" data-mode="slider" title="1">slider</button><button type="button" data-mode="flip" title="2 / f / click the image">flip</button><button type="button" data-mode="reference" title="3">reference</button><button type="button" data-mode="new" title="4">new</button>)HTML";
  h += str("<button type=\"button\" data-mode=\"diff\" title=\"5\">difference &times;", rep.options.diff_scale,
           "</button><button type=\"button\" data-mode=\"heat\" title=\"6\">heat map</button>");
  h += R"HTML(<label><input type="checkbox" id="v-autoflip"> flip every 0.5 s</label><label><input type="checkbox" id="v-actual"> actual pixels</label></div>
<div id="v-stage" class="stage"><div id="v-frame" class="frame"><img id="v-ref" alt="reference"><img id="v-new" alt="new"><img id="v-extra" alt="difference"><div id="v-divider"></div><span id="v-tag"></span></div></div>
<input type="range" id="v-slider" min="0" max="1000" value="500" aria-label="slider: reference on the left, new on the right">
<p id="v-reason"></p><table id="v-numbers"></table>
</section>
)HTML";

  h += "<section id=\"frames\"><h2>Frames</h2>\n<div class=\"controls\"><label>order <select id=\"order\">"
       "<option value=\"worst\">worst first</option><option value=\"sequence\">sequence</option></select></label>"
       "<label><input type=\"checkbox\" id=\"only-failing\"> failing frames only</label>";
  h += heat_legend() + "</div>\n";
  h += str("<table id=\"frame-table\"><thead><tr><th>#</th><th>frame</th><th>verdict</th><th>over ", t.fail,
           "/255</th><th>max</th><th>mean</th><th>PSNR dB</th><th>SSIM</th><th>reference</th><th>new</th>"
           "<th>heat map</th></tr></thead>\n<tbody>\n");
  const std::vector<size_t> order = worst_first(rep.results);
  for (size_t k = 0; k < order.size(); ++k) h += table_row(rep, rep.results[order[k]], k + 1, dir);
  h += "</tbody></table></section>\n";

  h += str("<footer><p>Differences: ", html_escape(kDifferenceDefinition), ". Mean: mean |reference &minus; new| over "
           "every channel value. ", html_escape(kPsnrDefinition), ". ", html_escape(kSsimDefinition), ". ",
           "Difference images: |reference &minus; new| &times; ", rep.options.diff_scale,
           ". Keys: j / k next / previous, f flip, 1&ndash;6 modes.</p>"
           "<p>Files: <a href=\"summary.csv\">summary.csv</a>, <a href=\"summary.json\">summary.json</a>.</p></footer>\n");
  h += str("<script type=\"application/json\" id=\"compare-data\">", frame_data_json(rep, dir), "</script>\n");
  h += str("<script>\n", kReportJs, "</script>\n</body>\n</html>\n");
  return h;
}

void write_report_html(const CompareReport& rep, const fs::path& dir) {
  const std::string page = report_html(rep, dir);
  write_file_atomically(dir / "report.html", [&](std::ostream& out) { out << page; });
}

}  // namespace spume::compare
