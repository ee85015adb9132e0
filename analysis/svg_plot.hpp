// Line plots as standalone SVG files (a browser or any image viewer opens them): one polyline
// with markers per series, grid lines and labels, a legend. Used by `afemp study` for error
// against wall time (log-log) and for a metric's value against the runs' resolution (linear).
#pragma once

#include <string>
#include <vector>

namespace afemp::analysis {

struct PlotSeries {
  std::string name;
  // Points that are not finite, and on log axes those with x <= 0 or y <= 0 (no logarithm),
  // are left out.
  std::vector<double> x, y;
  bool dashed = false;  // a reference drawn beside the measured lines
};

struct LinePlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
};

// The SVG document on log-log axes spanning whole decades around the plotted points (at least
// one).
std::string svg_loglog(const LinePlot& plot);
// The SVG document on linear axes from and to round ticks around the plotted points, a tick
// every 1, 2 or 5 times a power of ten (two to seven steps).
std::string svg_linear(const LinePlot& plot);

}  // namespace afemp::analysis
