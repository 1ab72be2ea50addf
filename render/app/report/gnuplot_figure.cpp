#include "render/app/report/gnuplot_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include "sim/core/atomic_file.h"
#include "sim/core/error.h"
#include "sim/core/child_process.h"

namespace spume::report {
namespace {

// Double-quoted gnuplot string: backslash and quote escaped. Enhanced text mode is off, so _ and ^
// in titles print as typed.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') {
      out += "\\n";
      continue;
    }
    out += c;
  }
  return out + "\"";
}

bool usable(double v, bool log_axis) { return std::isfinite(v) && (!log_axis || v > 0); }

}  // namespace

std::string gnuplot_script(const Figure& figure, const std::filesystem::path& png) {
  if (figure.panels.empty()) fail("report figure ", png.string(), ": no panels");
  const int columns = std::max(1, std::min<int>(figure.columns, int(figure.panels.size())));
  const int rows = int((figure.panels.size() + columns - 1) / columns);
  std::ostringstream s;
  s.precision(10);
  s << "set terminal pngcairo noenhanced size " << columns * figure.panel_width << ',' << rows * figure.panel_height
    << " font 'sans,10'\n";
  s << "set output " << quoted(png.string()) << "\n";
  s << "set datafile missing 'nan'\nset grid\n";
  // Data first: one datablock per series.
  for (size_t p = 0; p < figure.panels.size(); ++p) {
    const Panel& panel = figure.panels[p];
    for (size_t k = 0; k < panel.series.size(); ++k) {
      s << "$d" << p << '_' << k << " << EOD\n";
      for (const auto& [x, y] : panel.series[k].points)
        if (usable(x, panel.log_x) && usable(y, panel.log_y)) s << x << ' ' << y << '\n';
      s << "EOD\n";
    }
  }
  s << "set multiplot layout " << rows << ',' << columns << "\n";
  for (size_t p = 0; p < figure.panels.size(); ++p) {
    const Panel& panel = figure.panels[p];
    // Room below the plot for the key (two entries a row) under the x label.
    size_t longest = 0;
    for (const Series& series : panel.series) longest = std::max(longest, series.title.size());
    const size_t key_columns = longest > 30 ? 1 : 2;
    const size_t key_rows = (panel.series.size() + key_columns - 1) / key_columns;
    s << "unset logscale\nset autoscale\nset offsets 0, 0, graph 0.05, graph 0.05\nset bmargin " << 5 + key_rows
      << "\nset key below box maxcols " << key_columns << "\n";
    s << "set title " << quoted(panel.title) << "\nset xlabel " << quoted(panel.xlabel) << "\nset ylabel "
      << quoted(panel.ylabel) << "\n";
    if (panel.log_x) s << "set logscale x " << panel.log_x_base << "\n";
    if (panel.log_y) s << "set logscale y 10\n";
    s << "set format x '%g'\nset format y '%g'\n";
    s << (panel.reverse_x ? "set xrange [*:*] reverse\n" : "set xrange [*:*] noreverse\n");
    bool any = false;
    std::ostringstream plot;
    for (size_t k = 0; k < panel.series.size(); ++k) {
      bool has_point = false;
      for (const auto& [x, y] : panel.series[k].points) has_point |= usable(x, panel.log_x) && usable(y, panel.log_y);
      if (!has_point) continue;  // gnuplot refuses an empty datablock on a log axis
      const Series& series = panel.series[k];
      plot << (any ? ", " : "plot ") << "$d" << p << '_' << k << " using 1:2 with "
           << (series.dashed  ? "lines dt 2 lw 1.5"
               : series.lines ? "linespoints pt 7 ps 0.8 lw 1.5"
                              : "points pt 6 ps 1.4")
           << (series.color.empty() ? (series.lines ? "" : " lc rgb 'black'") : " lc rgb " + quoted(series.color))
           << " title " << quoted(series.title);
      any = true;
    }
    if (any) s << plot.str() << "\n";
    else s << "set label 1 'no data' at graph 0.5, 0.5 center\nplot 2 notitle with lines lc rgb 'white'\nunset label 1\n";
  }
  s << "unset multiplot\nset output\n";
  return s.str();
}

void draw_figure(const Figure& figure, const std::filesystem::path& png, const std::filesystem::path& script_path) {
  // Hidden temporaries beside the PNG (same file system, so the rename is atomic).
  const std::string hidden = str(".", png.filename().string());
  const std::filesystem::path temporary = png.parent_path() / str(hidden, ".tmp.png");
  const std::string script = gnuplot_script(figure, temporary);
  // Keep the script with the PNG's own name in it, so running it by hand redraws the real file.
  write_file_atomically(script_path, [&](std::ostream& out) { out << gnuplot_script(figure, png); });
  const std::filesystem::path run_script = png.parent_path() / str(hidden, ".tmp.gp");
  write_file_atomically(run_script, [&](std::ostream& out) { out << script; });
  const ProcessResult run = run_process({"gnuplot", run_script.string()});
  std::error_code ec;
  std::filesystem::remove(run_script, ec);
  if (!run.started)
    fail("gnuplot could not be run (", run.start_error,
         "): the report draws its plots with gnuplot; install the Debian package gnuplot-nox");
  if (run.exit_code != 0 || !std::filesystem::is_regular_file(temporary)) {
    std::filesystem::remove(temporary, ec);
    fail(png.string(), ": gnuplot failed on ", script_path.string(), ":\n", run.output);
  }
  std::filesystem::rename(temporary, png, ec);
  if (ec) fail(png.string(), ": cannot rename the plot into place: ", ec.message());
}

}  // namespace spume::report
