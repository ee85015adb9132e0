#include "analysis/taylor_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace afemp::analysis {

namespace {

const CylinderShape& taylor_bar(const BodySpec& spec) {
  const auto* cyl = std::get_if<CylinderShape>(&spec.shape);
  if (cyl == nullptr)
    throw std::invalid_argument("Taylor measures need a cylinder body; '" + spec.name +
                                "' is not one");
  if (cyl->nose.crh > 0.0)
    throw std::invalid_argument("Taylor measures need a flat-ended cylinder; '" + spec.name +
                                "' has a nose");
  return *cyl;
}

// Half an initial element length along the axis of a meshed bar.
double element_band(const BodySpec& spec, const CylinderShape& bar) {
  return 0.5 * bar.length /
         std::max(1,
                  spec.mesh.axial > 0
                      ? spec.mesh.axial
                      : static_cast<int>(std::ceil(bar.length / std::max(spec.mesh.size, 1e-300))));
}

}  // namespace

TaylorMeasures measure_taylor(const Scene& scene, int body, std::span<const Vec3> points,
                              std::span<const double> half) {
  const BodySpec& spec = scene.bodies.at(static_cast<std::size_t>(body));
  const CylinderShape& bar = taylor_bar(spec);
  if (points.empty()) throw std::invalid_argument("body '" + spec.name + "' has no points left");
  const Vec3 axis = (1.0 / norm(bar.axis)) * bar.axis;
  auto axial = [&](std::size_t i) { return dot(points[i] - bar.base, axis); };
  auto radial = [&](std::size_t i) {
    const Vec3 d = points[i] - bar.base;
    return norm(d - dot(d, axis) * axis);
  };

  double lo = 1e300, hi = -1e300;
  double band = spec.discretisation == Discretisation::particles ? 0.0 : element_band(spec, bar);
  for (std::size_t i = 0; i < points.size(); ++i) {
    lo = std::min(lo, axial(i) - half[i]);
    hi = std::max(hi, axial(i) + half[i]);
    band = std::max(band, half[i]);  // half of the largest spacing
  }
  // The wall end: the end nearer the cylinder base (the base sits on the wall).
  const double station = lo + 0.2 * bar.length;
  double r_face = 0.0, r_bulge = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double a = axial(i), r = radial(i) + half[i];
    if (a - half[i] <= lo + band) r_face = std::max(r_face, r);
    if (std::abs(a - station) <= band) r_bulge = std::max(r_bulge, r);
  }
  return {hi - lo, 2.0 * r_face, 2.0 * r_bulge};
}

double taylor_mean_error(const TaylorMeasures& m, const TaylorReference& ref) {
  return (std::abs(m.length - ref.length) / ref.length +
          std::abs(m.impact_diameter - ref.impact_diameter) / ref.impact_diameter +
          std::abs(m.bulge_diameter - ref.bulge_diameter) / ref.bulge_diameter) /
         3.0;
}

}  // namespace afemp::analysis
