#include "analysis/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>

#include "core/appendf.hpp"
#include "core/output/xml_escape.hpp"

namespace afemp::analysis {

using core::appendf;
using core::xml_escape;

namespace {

constexpr const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd",
                                   "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};
constexpr const char* markers[] = {"circle", "square", "diamond", "triangle"};

void marker(std::string& out, const char* shape, double x, double y, const char* colour) {
  const double r = 4.5;
  if (std::string(shape) == "circle") {
    appendf(out, "<circle cx=\"%.2f\" cy=\"%.2f\" r=\"%.1f\" fill=\"%s\"/>\n", x, y, r, colour);
  } else if (std::string(shape) == "square") {
    appendf(out, "<rect x=\"%.2f\" y=\"%.2f\" width=\"%.1f\" height=\"%.1f\" fill=\"%s\"/>\n",
            x - r, y - r, 2 * r, 2 * r, colour);
  } else if (std::string(shape) == "diamond") {
    appendf(out, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\"/>\n", x,
            y - 1.3 * r, x + 1.3 * r, y, x, y + 1.3 * r, x - 1.3 * r, y, colour);
  } else {
    appendf(out, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\"/>\n", x,
            y - 1.3 * r, x + 1.2 * r, y + r, x - 1.2 * r, y + r, colour);
  }
}

// One axis: where a value falls along it (0 at the low end, 1 at the high end) and its grid
// lines, labelled (major) or faint (minor).
struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;  // the ends; on a log axis their decade exponents
  std::vector<double> major, minor;
  bool shows(double v) const { return std::isfinite(v) && (!log || v > 0.0); }
  double fraction(double v) const { return ((log ? std::log10(v) : v) - lo) / (hi - lo); }
};

// Whole decades from below `min` to above `max`, 2..9 times each decade faint.
Axis log_axis(double min, double max) {
  Axis a;
  a.log = true;
  if (!(min <= max)) min = 1.0, max = 10.0;  // nothing to plot
  const int k0 = static_cast<int>(std::floor(std::log10(min)));
  const int k1 = std::max(k0 + 1, static_cast<int>(std::ceil(std::log10(max))));
  a.lo = k0, a.hi = k1;
  for (int k = k0; k <= k1; ++k) {
    a.major.push_back(std::pow(10.0, k));
    for (int m = 2; m <= 9 && k < k1; ++m) a.minor.push_back(m * std::pow(10.0, k));
  }
  return a;
}

// Round ticks around [min, max]: the step is 1, 2 or 5 times a power of ten, the first of
// those at least a fifth of the span, so that the labels read as the numbers they are.
Axis linear_axis(double min, double max) {
  Axis a;
  if (!(min <= max)) min = 0.0, max = 1.0;  // nothing to plot
  // One value (or one level): a span of 10 % about it.
  if (min == max) {
    const double pad = min == 0.0 ? 1.0 : 0.1 * std::abs(min);
    min -= pad, max += pad;
  }
  const double raw = (max - min) / 5.0;
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  // A span or a bound a rounding error past a round number does not take the next step.
  const double m = raw / decade * (1.0 - 1e-9);
  const double step = (m <= 1.0 ? 1.0 : m <= 2.0 ? 2.0 : m <= 5.0 ? 5.0 : 10.0) * decade;
  const long k0 = std::lround(std::floor(min / step + 1e-9));
  const long k1 = std::lround(std::ceil(max / step - 1e-9));
  a.lo = static_cast<double>(k0) * step, a.hi = static_cast<double>(k1) * step;
  for (long k = k0; k <= k1; ++k) a.major.push_back(static_cast<double>(k) * step);
  return a;
}

std::string tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// The ends of each axis from the points both axes show.
void data_range(const LinePlot& plot, bool log, double& x_min, double& x_max, double& y_min,
                double& y_max) {
  Axis probe;
  probe.log = log;
  x_min = y_min = std::numeric_limits<double>::infinity();
  x_max = y_max = -std::numeric_limits<double>::infinity();
  for (const PlotSeries& s : plot.series)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (probe.shows(s.x[i]) && probe.shows(s.y[i])) {
        x_min = std::min(x_min, s.x[i]);
        x_max = std::max(x_max, s.x[i]);
        y_min = std::min(y_min, s.y[i]);
        y_max = std::max(y_max, s.y[i]);
      }
}

std::string svg(const LinePlot& plot, const Axis& ax, const Axis& ay) {
  const double width = 720, height = 480, left = 80, right = 190, top = 50, bottom = 60;
  const double pw = width - left - right, ph = height - top - bottom;
  auto px = [&](double x) { return left + pw * ax.fraction(x); };
  auto py = [&](double y) { return top + ph * (1.0 - ay.fraction(y)); };

  std::string out;
  appendf(out,
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
          "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"13\">\n",
          width, height, width, height);
  appendf(out, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
  // User text goes in with +=: appendf's buffer is short.
  appendf(out, "<text x=\"%.1f\" y=\"28\" text-anchor=\"middle\" font-size=\"15\">", left + pw / 2);
  out += xml_escape(plot.title) + "</text>\n";
  // Grid: the faint lines first, so that the labelled ones lie on top.
  for (const double x : ax.minor)
    appendf(out, "<line x1=\"%.2f\" y1=\"%.1f\" x2=\"%.2f\" y2=\"%.1f\" stroke=\"#eeeeee\"/>\n",
            px(x), top, px(x), top + ph);
  for (const double y : ay.minor)
    appendf(out, "<line x1=\"%.1f\" y1=\"%.2f\" x2=\"%.1f\" y2=\"%.2f\" stroke=\"#eeeeee\"/>\n",
            left, py(y), left + pw, py(y));
  for (const double x : ax.major) {
    appendf(out, "<line x1=\"%.2f\" y1=\"%.1f\" x2=\"%.2f\" y2=\"%.1f\" stroke=\"#bbbbbb\"/>\n",
            px(x), top, px(x), top + ph);
    appendf(out, "<text x=\"%.2f\" y=\"%.1f\" text-anchor=\"middle\">%s</text>\n", px(x),
            top + ph + 20, tick_label(x).c_str());
  }
  for (const double y : ay.major) {
    appendf(out, "<line x1=\"%.1f\" y1=\"%.2f\" x2=\"%.1f\" y2=\"%.2f\" stroke=\"#bbbbbb\"/>\n",
            left, py(y), left + pw, py(y));
    appendf(
        out,
        "<text x=\"%.1f\" y=\"%.2f\" text-anchor=\"end\" dominant-baseline=\"middle\">%s</text>\n",
        left - 8, py(y), tick_label(y).c_str());
  }
  appendf(out,
          "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
          "stroke=\"black\"/>\n",
          left, top, pw, ph);
  appendf(out, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", left + pw / 2, height - 15);
  out += xml_escape(plot.x_label) + "</text>\n";
  appendf(out,
          "<text x=\"20\" y=\"%.1f\" text-anchor=\"middle\" transform=\"rotate(-90 20 %.1f)\">",
          top + ph / 2, top + ph / 2);
  out += xml_escape(plot.y_label) + "</text>\n";
  // Series and legend.
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    const char* colour = palette[k % std::size(palette)];
    const char* shape = markers[k % std::size(markers)];
    const std::string stroke = std::string("\" stroke=\"") + colour + "\" stroke-width=\"2\"" +
                               (s.dashed ? " stroke-dasharray=\"6 4\"" : "") + "/>\n";
    std::string points;
    std::vector<std::pair<double, double>> kept;
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (ax.shows(s.x[i]) && ay.shows(s.y[i])) kept.emplace_back(px(s.x[i]), py(s.y[i]));
    out += "<g class=\"series\" data-name=\"" + xml_escape(s.name) + "\">\n";
    for (const auto& [x, y] : kept) appendf(points, "%.2f,%.2f ", x, y);
    if (kept.size() > 1)  // appendf's buffer is too short for a long point list
      out += "<polyline points=\"" + points + "\" fill=\"none" + stroke;
    for (const auto& [x, y] : kept) marker(out, shape, x, y, colour);
    out += "</g>\n";
    const double ly = top + 12 + 24 * static_cast<double>(k);
    appendf(out, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f", left + pw + 15, ly,
            left + pw + 45, ly);
    out += stroke;
    marker(out, shape, left + pw + 30, ly, colour);
    appendf(out, "<text x=\"%.1f\" y=\"%.1f\" dominant-baseline=\"middle\">", left + pw + 52, ly);
    out += xml_escape(s.name) + "</text>\n";
  }
  out += "</svg>\n";
  return out;
}

}  // namespace

std::string svg_loglog(const LinePlot& plot) {
  double x_min, x_max, y_min, y_max;
  data_range(plot, true, x_min, x_max, y_min, y_max);
  return svg(plot, log_axis(x_min, x_max), log_axis(y_min, y_max));
}

std::string svg_linear(const LinePlot& plot) {
  double x_min, x_max, y_min, y_max;
  data_range(plot, false, x_min, x_max, y_min, y_max);
  return svg(plot, linear_axis(x_min, x_max), linear_axis(y_min, y_max));
}

}  // namespace afemp::analysis
