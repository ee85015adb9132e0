// A log-log line plot as a standalone SVG file (a browser or any image viewer opens it): one
// polyline with markers per series, decade grid lines and labels, a legend. Used by
// `afemp study` for error against wall time.
#pragma once

#include <string>
#include <vector>

namespace afemp::analysis {

struct PlotSeries {
  std::string name;
  std::vector<double> x, y;  // points with x <= 0 or y <= 0 (no logarithm) are left out
};

struct LogLogPlot {
  std::string title, x_label, y_label;
  std::vector<PlotSeries> series;
};

// The SVG document. Axes span whole decades around the plotted points (at least one).
std::string svg_loglog(const LogLogPlot& plot);

}  // namespace afemp::analysis
