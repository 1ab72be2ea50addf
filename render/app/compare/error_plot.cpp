#include "render/app/compare/error_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/app/compare/html_text.h"
#include "render/app/compare/summary_files.h"

namespace spume::compare {
namespace {

constexpr double kWidth = 960, kLeft = 78, kRight = 16, kPanelHeight = 118, kTop1 = 26, kGap = 40;
constexpr double kTop2 = kTop1 + kPanelHeight + kGap, kHeight = kTop2 + kPanelHeight + 40;
// Above this many frames only failing frames get a marker of their own; the line shows the rest.
constexpr size_t kMaxMarkers = 1500;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

struct Panel {
  double top;
  std::string title;
};

// Maps a value to a height fraction in [0, 1] of its panel.
struct Scale {
  double lo_decade = -4;  // share panel: log10 of the lowest decade shown
  double share(double percent) const {
    if (percent <= 0) return 0.0;
    // Zero sits on the axis; the lowest decade 8% of the way up, 100% at the top.
    const double f = (std::log10(percent) - lo_decade) / (2.0 - lo_decade);
    return 0.08 + 0.92 * std::clamp(f, 0.0, 1.0);
  }
  static double level(double d) { return std::log2(1.0 + d) / 8.0; }
};

std::string share_label(double decade) {
  const double v = std::pow(10.0, decade);
  char buf[32];
  if (decade >= 0) std::snprintf(buf, sizeof buf, "%.0f%%", v);
  else std::snprintf(buf, sizeof buf, "%.*f%%", int(-decade), v);
  return buf;
}

}  // namespace

std::string error_plot_svg(const std::vector<FrameResult>& results, const CompareThresholds& t) {
  const size_t n = results.size();
  const double plot_w = kWidth - kLeft - kRight;
  auto x_of = [&](size_t i) { return kLeft + (double(i) + 0.5) * plot_w / double(std::max<size_t>(n, 1)); };
  Scale scale;
  double smallest = t.failpercent.value() > 0 ? t.failpercent.value() : 100.0;
  for (const FrameResult& r : results)
    if (r.compared && r.stats.over_fail > 0) smallest = std::min(smallest, r.stats.over_fail_percent());
  scale.lo_decade = std::clamp(std::floor(std::log10(smallest)), -7.0, 1.0);
  auto y_share = [&](double p) { return kTop1 + kPanelHeight * (1.0 - scale.share(p)); };
  auto y_level = [&](double d) { return kTop2 + kPanelHeight * (1.0 - Scale::level(d)); };

  std::string s = str("<svg id=\"error-plot\" viewBox=\"0 0 ", num(kWidth), " ", num(kHeight),
                      "\" role=\"img\" aria-label=\"error over the sequence\" data-left=\"", num(kLeft),
                      "\" data-width=\"", num(plot_w), "\" data-frames=\"", n, "\">\n");
  // Axes, grid and labels.
  const Panel panels[2] = {{kTop1, str("pixels over ", t.fail, "/255, % of the frame (log scale)")},
                           {kTop2, "largest difference, 8-bit levels (log scale)"}};
  for (const Panel& p : panels) {
    s += str("<rect class=\"panel\" x=\"", num(kLeft), "\" y=\"", num(p.top), "\" width=\"", num(plot_w), "\" height=\"",
             num(kPanelHeight), "\"/>\n");
    s += str("<text class=\"title\" x=\"", num(kLeft), "\" y=\"", num(p.top - 8), "\">", html_escape(p.title), "</text>\n");
  }
  auto grid = [&](double y, const std::string& label) {
    s += str("<line class=\"grid\" x1=\"", num(kLeft), "\" x2=\"", num(kLeft + plot_w), "\" y1=\"", num(y), "\" y2=\"",
             num(y), "\"/><text class=\"tick\" x=\"", num(kLeft - 6), "\" y=\"", num(y + 4), "\">", label, "</text>\n");
  };
  grid(y_share(0), "0");
  const int decades = int(2 - scale.lo_decade);
  const int step = decades > 6 ? 2 : 1;
  for (int k = 0; k <= decades; k += step) grid(y_share(std::pow(10.0, scale.lo_decade + k)), share_label(scale.lo_decade + k));
  for (int d : {0, 1, 3, 15, 63, 255}) grid(y_level(d), std::to_string(d));
  // Thresholds.
  auto threshold = [&](double y, const std::string& label) {
    s += str("<line class=\"threshold\" x1=\"", num(kLeft), "\" x2=\"", num(kLeft + plot_w), "\" y1=\"", num(y),
             "\" y2=\"", num(y), "\"/><text class=\"threshold-label\" x=\"", num(kLeft + plot_w - 4), "\" y=\"",
             num(y - 4), "\">", html_escape(label), "</text>\n");
  };
  threshold(y_share(t.failpercent.value()), str("--failpercent ", t.failpercent.text(), "%"));
  threshold(y_level(t.hardfail), str("--hardfail ", t.hardfail));

  // Frame labels on the x axis: about ten, at the first and last frame and evenly between.
  const size_t ticks = std::min<size_t>(n, 10);
  for (size_t k = 0; k < ticks; ++k) {
    const size_t i = ticks == 1 ? 0 : (k * (n - 1) + (ticks - 1) / 2) / (ticks - 1);
    const FramePair& p = results[i].pair;
    const std::string label = p.number ? std::to_string(*p.number) : p.stem;
    s += str("<text class=\"xtick\" x=\"", num(x_of(i)), "\" y=\"", num(kTop2 + kPanelHeight + 16), "\">",
             html_escape(label), "</text>\n");
  }
  s += str("<text class=\"xtitle\" x=\"", num(kLeft + plot_w / 2), "\" y=\"", num(kHeight - 6), "\">frame</text>\n");

  // The two series: one polyline per run of compared frames, then markers.
  for (int panel = 0; panel < 2; ++panel) {
    std::string points;
    auto flush = [&] {
      if (!points.empty()) s += str("<polyline class=\"series\" points=\"", points, "\"/>\n");
      points.clear();
    };
    for (const FrameResult& r : results) {
      if (!r.compared) {
        flush();
        continue;
      }
      const double y = panel == 0 ? y_share(r.stats.over_fail_percent()) : y_level(r.stats.max_diff);
      points += str(points.empty() ? "" : " ", num(x_of(r.index)), ",", num(y));
    }
    flush();
  }
  s += "<g class=\"markers\">\n";
  for (const FrameResult& r : results) {
    const std::string name = html_escape(r.pair.label);
    const char* cls = r.passed() ? "pass" : "fail";
    if (!r.compared) {
      // A triangle above each panel: the frame has no figures.
      for (double top : {kTop1, kTop2}) {
        const double x = x_of(r.index), y = top - 2;
        s += str("<path class=\"marker problem\" data-index=\"", r.index, "\" d=\"M", num(x - 4), " ", num(y - 7), "H",
                 num(x + 4), "L", num(x), " ", num(y), "Z\"><title>", name, ": ", html_escape(r.reason),
                 "</title></path>\n");
      }
      continue;
    }
    if (r.passed() && n > kMaxMarkers) continue;
    const std::string tip = str(name, ": ", status_code(r.status), ", ", format_fixed(r.stats.over_fail_percent(), 4),
                                "% over ", t.fail, "/255, max ", r.stats.max_diff, "/255");
    s += str("<circle class=\"marker ", cls, "\" data-index=\"", r.index, "\" cx=\"", num(x_of(r.index)), "\" cy=\"",
             num(y_share(r.stats.over_fail_percent())), "\" r=\"3\"><title>", tip, "</title></circle>\n");
    s += str("<circle class=\"marker ", cls, "\" data-index=\"", r.index, "\" cx=\"", num(x_of(r.index)), "\" cy=\"",
             num(y_level(r.stats.max_diff)), "\" r=\"3\"><title>", tip, "</title></circle>\n");
  }
  s += "</g>\n";
  s += str("<line id=\"plot-cursor\" x1=\"0\" x2=\"0\" y1=\"", num(kTop1), "\" y2=\"", num(kTop2 + kPanelHeight),
           "\" visibility=\"hidden\"/>\n");
  if (n == 0) s += str("<text class=\"empty\" x=\"", num(kWidth / 2), "\" y=\"", num(kHeight / 2), "\">no frames</text>\n");
  return s + "</svg>\n";
}

}  // namespace spume::compare
