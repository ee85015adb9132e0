// The SVG line plots (analysis/svg_plot.hpp): linear axes tick at round steps (1, 2 or 5 times
// a power of ten) from and to the ticks around the points, log-log axes at whole decades, and
// each point lands where its value falls between the axis ends (the plot area spans x 80..530
// and y 50..420 of the 720 x 480 document); a dashed series is dashed in its line and legend.
#include <gtest/gtest.h>

#include <string>

#include "analysis/svg_plot.hpp"

namespace afemp::analysis {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

bool has_tick(const std::string& svg, const std::string& label) {
  return svg.find("\">" + label + "</text>") != std::string::npos;
}

TEST(SvgPlot, LinearAxesTickAtRoundStepsAndPlaceThePointsBetweenThem) {
  LinePlot plot;
  plot.title = "hole";
  plot.x_label = "impact speed (km/s)";
  plot.series.push_back({"MPM", {1, 2, 3, 4}, {10, 12, 15, 19}, false});
  plot.series.push_back({"reference", {1, 4}, {11, 11}, true});
  const std::string svg = svg_linear(plot);
  // x: span 3, a fifth 0.6: step 1, ticks 1..4. y: span 9, a fifth 1.8: step 2, ticks 10..20.
  for (const char* t : {"1", "2", "3", "4", "10", "12", "14", "16", "18", "20"})
    EXPECT_TRUE(has_tick(svg, t)) << t;
  for (const char* t : {"0", "5", "8", "22"}) EXPECT_FALSE(has_tick(svg, t)) << t;
  // (2, 12): a third of the way along x, a fifth of the way up y.
  EXPECT_NE(svg.find("<circle cx=\"230.00\" cy=\"346.00\""), std::string::npos) << svg;
  EXPECT_EQ(count(svg, "<g class=\"series\""), 2u);
  EXPECT_NE(svg.find("data-name=\"reference\""), std::string::npos);
  EXPECT_EQ(count(svg, "stroke-dasharray=\"6 4\""), 2u);  // its polyline and its legend line
  EXPECT_NE(svg.find(">impact speed (km/s)</text>"), std::string::npos);
}

TEST(SvgPlot, LinearAxesAboutOneLevelSpanTenPercentOfIt) {
  LinePlot plot;
  plot.series.push_back({"band", {0.5, 0.5}, {-4, -4}, false});
  const std::string svg = svg_linear(plot);
  // x: 0.45..0.55, step 0.02; y: -4.4..-3.6, step 0.2, from -4.4 to -3.6.
  for (const char* t : {"0.44", "0.5", "0.56", "-4.4", "-4", "-3.6"})
    EXPECT_TRUE(has_tick(svg, t)) << t;
  EXPECT_FALSE(has_tick(svg, "-3.4"));
  EXPECT_FALSE(has_tick(svg, "-4.6"));
}

TEST(SvgPlot, LogLogAxesSpanWholeDecades) {
  LinePlot plot;
  plot.series.push_back(
      {"FE", {0.5, 1, 20, 30}, {0.002, 0.01, 0.03, 0.0}, false});  // y = 0: left out
  const std::string svg = svg_loglog(plot);
  for (const char* t : {"0.1", "1", "10", "100", "0.001", "0.01", "0.1"})
    EXPECT_TRUE(has_tick(svg, t)) << t;
  EXPECT_FALSE(has_tick(svg, "1000"));
  EXPECT_FALSE(has_tick(svg, "0.0001"));
  // (1, 0.01): one decade of three along x, one of two up y.
  EXPECT_NE(svg.find("<circle cx=\"230.00\" cy=\"235.00\""), std::string::npos) << svg;
  EXPECT_EQ(count(svg, "<circle"), 4u);  // three points and the legend's marker
  EXPECT_EQ(count(svg, "stroke-dasharray"), 0u);
}

}  // namespace
}  // namespace afemp::analysis
