#pragma once
// A study's plot, drawn by gnuplot (Debian gnuplot-nox) as a PNG: spume writes a script with the data
// inline (datablocks) and runs `gnuplot SCRIPT` as a subprocess. The script is kept beside the PNG
// so a reader can restyle the plot. The PNG is drawn under a temporary name and renamed into place.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace spume::report {

struct Series {
  Series() = default;
  Series(std::string title_, std::vector<std::pair<double, double>> points_ = {}, bool lines_ = true,
         bool dashed_ = false, std::string color_ = {})
      : title(std::move(title_)), points(std::move(points_)), lines(lines_), dashed(dashed_), color(std::move(color_)) {}

  std::string title;
  std::vector<std::pair<double, double>> points;  // (x, y); on log axes non-positive values are left out
  bool lines = true;                              // false: points only (measured reference data)
  bool dashed = false;                            // a level drawn for comparison (a floor, a reference cost)
  std::string color;                              // gnuplot colour name; empty: the default cycle
};

struct Panel {
  std::string title, xlabel, ylabel;  // labels carry the units
  bool log_x = false, log_y = false;
  bool reverse_x = false;             // e.g. a step size that shrinks to the right
  std::vector<Series> series;
  int log_x_base = 10;                // 2 for steps that halve
};

struct Figure {
  std::vector<Panel> panels;
  int columns = 1;
  int panel_width = 640, panel_height = 420;  // pixels
};

// The gnuplot script that draws `figure` into `png` (the pngcairo terminal).
std::string gnuplot_script(const Figure& figure, const std::filesystem::path& png);

// Writes `script_path` and runs gnuplot on it, producing `png` atomically. Throws Error when gnuplot
// is missing (naming the Debian package) or fails (with its message).
void draw_figure(const Figure& figure, const std::filesystem::path& png, const std::filesystem::path& script_path);

}  // namespace spume::report
