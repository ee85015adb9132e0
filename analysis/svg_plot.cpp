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
    appendf(out, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\"/>\n",
            x, y - 1.3 * r, x + 1.3 * r, y, x, y + 1.3 * r, x - 1.3 * r, y, colour);
  } else {
    appendf(out, "<polygon points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\"/>\n", x,
            y - 1.3 * r, x + 1.2 * r, y + r, x - 1.2 * r, y + r, colour);
  }
}

std::string decade_label(int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, k));
  return buf;
}

}  // namespace

std::string svg_loglog(const LogLogPlot& plot) {
  double x_min = std::numeric_limits<double>::infinity(), x_max = 0.0;
  double y_min = std::numeric_limits<double>::infinity(), y_max = 0.0;
  for (const PlotSeries& s : plot.series)
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (s.x[i] > 0.0 && s.y[i] > 0.0 && std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x_min = std::min(x_min, s.x[i]);
        x_max = std::max(x_max, s.x[i]);
        y_min = std::min(y_min, s.y[i]);
        y_max = std::max(y_max, s.y[i]);
      }
  if (!(x_max > 0.0)) x_min = 1.0, x_max = 10.0, y_min = 1.0, y_max = 10.0;  // nothing to plot
  const int x0 = static_cast<int>(std::floor(std::log10(x_min)));
  const int x1 = std::max(x0 + 1, static_cast<int>(std::ceil(std::log10(x_max))));
  const int y0 = static_cast<int>(std::floor(std::log10(y_min)));
  const int y1 = std::max(y0 + 1, static_cast<int>(std::ceil(std::log10(y_max))));
  const double width = 720, height = 480, left = 80, right = 190, top = 50, bottom = 60;
  const double pw = width - left - right, ph = height - top - bottom;
  auto px = [&](double x) { return left + pw * (std::log10(x) - x0) / (x1 - x0); };
  auto py = [&](double y) { return top + ph * (1.0 - (std::log10(y) - y0) / (y1 - y0)); };

  std::string out;
  appendf(out,
          "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" "
          "viewBox=\"0 0 %.0f %.0f\" font-family=\"sans-serif\" font-size=\"13\">\n",
          width, height, width, height);
  appendf(out, "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n");
  // User text goes in with +=: appendf's buffer is short.
  appendf(out, "<text x=\"%.1f\" y=\"28\" text-anchor=\"middle\" font-size=\"15\">", left + pw / 2);
  out += xml_escape(plot.title) + "</text>\n";
  // Grid: decades solid, 2..9 faint.
  for (int k = x0; k <= x1; ++k) {
    for (int m = 1; m <= (k < x1 ? 9 : 1); ++m) {
      const double x = px(m * std::pow(10.0, k));
      appendf(out, "<line x1=\"%.2f\" y1=\"%.1f\" x2=\"%.2f\" y2=\"%.1f\" stroke=\"%s\"/>\n", x,
              top, x, top + ph, m == 1 ? "#bbbbbb" : "#eeeeee");
    }
    appendf(out, "<text x=\"%.2f\" y=\"%.1f\" text-anchor=\"middle\">%s</text>\n", px(std::pow(10.0, k)),
            top + ph + 20, decade_label(k).c_str());
  }
  for (int k = y0; k <= y1; ++k) {
    for (int m = 1; m <= (k < y1 ? 9 : 1); ++m) {
      const double y = py(m * std::pow(10.0, k));
      appendf(out, "<line x1=\"%.1f\" y1=\"%.2f\" x2=\"%.1f\" y2=\"%.2f\" stroke=\"%s\"/>\n", left,
              y, left + pw, y, m == 1 ? "#bbbbbb" : "#eeeeee");
    }
    appendf(out, "<text x=\"%.1f\" y=\"%.2f\" text-anchor=\"end\" dominant-baseline=\"middle\">%s</text>\n",
            left - 8, py(std::pow(10.0, k)), decade_label(k).c_str());
  }
  appendf(out, "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" stroke=\"black\"/>\n",
          left, top, pw, ph);
  appendf(out, "<text x=\"%.1f\" y=\"%.1f\" text-anchor=\"middle\">", left + pw / 2, height - 15);
  out += xml_escape(plot.x_label) + "</text>\n";
  appendf(out, "<text x=\"20\" y=\"%.1f\" text-anchor=\"middle\" transform=\"rotate(-90 20 %.1f)\">",
          top + ph / 2, top + ph / 2);
  out += xml_escape(plot.y_label) + "</text>\n";
  // Series and legend.
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    const char* colour = palette[k % std::size(palette)];
    const char* shape = markers[k % std::size(markers)];
    std::string points;
    std::vector<std::pair<double, double>> kept;
    for (std::size_t i = 0; i < s.x.size(); ++i)
      if (s.x[i] > 0.0 && s.y[i] > 0.0 && std::isfinite(s.x[i]) && std::isfinite(s.y[i]))
        kept.emplace_back(px(s.x[i]), py(s.y[i]));
    out += "<g class=\"series\" data-name=\"" + xml_escape(s.name) + "\">\n";
    for (const auto& [x, y] : kept) appendf(points, "%.2f,%.2f ", x, y);
    if (kept.size() > 1)  // appendf's buffer is too short for a long point list
      out += "<polyline points=\"" + points + "\" fill=\"none\" stroke=\"" + colour +
             "\" stroke-width=\"2\"/>\n";
    for (const auto& [x, y] : kept) marker(out, shape, x, y, colour);
    out += "</g>\n";
    const double ly = top + 12 + 24 * static_cast<double>(k);
    appendf(out, "<line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" stroke-width=\"2\"/>\n",
            left + pw + 15, ly, left + pw + 45, ly, colour);
    marker(out, shape, left + pw + 30, ly, colour);
    appendf(out, "<text x=\"%.1f\" y=\"%.1f\" dominant-baseline=\"middle\">", left + pw + 52, ly);
    out += xml_escape(s.name) + "</text>\n";
  }
  out += "</svg>\n";
  return out;
}

}  // namespace afemp::analysis
