// Crater and hole measures (analysis/crater_metrics.hpp).
#include "analysis/crater_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/material_column.hpp"

namespace afemp::analysis {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// Height along the axis and distance from it.
struct AxisCoordinates {
  double h, r;
};
AxisCoordinates about_axis(const Vec3& x, const Vec3& point, const Vec3& normal) {
  const Vec3 d = x - point;
  const double h = dot(d, normal);
  return {h, norm(d - h * normal)};
}

}  // namespace

double surface_level(std::span<const Vec3> points, const Vec3& point, const Vec3& normal) {
  double top = -inf;
  for (const Vec3& x : points) top = std::max(top, dot(x - point, normal));
  return top;
}

CraterMeasures measure_crater(std::span<const Vec3> points, const Vec3& point, const Vec3& normal,
                              double initial_level, double ring, double threshold) {
  std::vector<std::vector<double>> heights;
  for (const Vec3& x : points) {
    const AxisCoordinates c = about_axis(x, point, normal);
    const auto k = static_cast<std::size_t>(c.r / ring);
    if (k >= heights.size()) heights.resize(k + 1);
    heights[k].push_back(c.h);
  }
  std::vector<double> drop(heights.size(), inf);
  for (std::size_t k = 0; k < heights.size(); ++k) {
    if (heights[k].empty()) continue;
    drop[k] = initial_level - material_column_top(heights[k], ring);
  }
  CraterMeasures m;
  m.depth = drop.empty() || std::isinf(drop[0]) ? std::nan("") : drop[0];
  std::size_t k = 0;
  while (k < drop.size() && drop[k] > threshold) ++k;
  double radius = 0.0;
  if (k == drop.size()) {
    radius = static_cast<double>(k) * ring;  // every ring dropped: the outermost's outer edge
  } else if (k > 0) {
    const double inner = drop[k - 1], outer = drop[k];
    const double centre = (static_cast<double>(k) - 0.5) * ring;
    radius = std::isinf(inner) ? static_cast<double>(k) * ring
                               : centre + (inner - threshold) / (inner - outer) * ring;
  }
  m.diameter = 2.0 * radius;
  return m;
}

double measure_hole(std::span<const Vec3> points, const Vec3& point, const Vec3& normal,
                    double band) {
  double r_min = inf;
  for (const Vec3& x : points) {
    const AxisCoordinates c = about_axis(x, point, normal);
    if (std::abs(c.h) <= band) r_min = std::min(r_min, c.r);
  }
  return std::isinf(r_min) ? std::nan("") : 2.0 * r_min;
}

}  // namespace afemp::analysis
