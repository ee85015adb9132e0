#include "core/taylor_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace afemp::core {

TaylorMeasures measure_taylor(std::span<const Vec3> points, std::span<const double> half,
                              const CylinderShape& bar, double face_band) {
  const Vec3 axis = (1.0 / norm(bar.axis)) * bar.axis;
  auto axial = [&](std::size_t i) { return dot(points[i] - bar.base, axis); };
  auto radial = [&](std::size_t i) {
    const Vec3 d = points[i] - bar.base;
    return norm(d - dot(d, axis) * axis);
  };
  auto h = [&](std::size_t i) { return half.empty() ? 0.0 : half[i]; };
  if (points.empty()) throw std::invalid_argument("Taylor measures need the points of the bar");

  double lo = 1e300, hi = -1e300, band = face_band;
  for (std::size_t i = 0; i < points.size(); ++i) {
    lo = std::min(lo, axial(i) - h(i));
    hi = std::max(hi, axial(i) + h(i));
    band = std::max(band, h(i));  // half of the largest spacing
  }
  // The wall end: the end nearer the cylinder base (the base sits on the wall).
  const double station = lo + 0.2 * bar.length;
  double r_face = 0.0, r_bulge = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double a = axial(i), r = radial(i) + h(i);
    if (a - h(i) <= lo + band) r_face = std::max(r_face, r);
    if (std::abs(a - station) <= band) r_bulge = std::max(r_bulge, r);
  }
  return {hi - lo, 2.0 * r_face, 2.0 * r_bulge};
}

const CylinderShape& taylor_bar(const Scene& scene, int body) {
  const BodySpec& spec = scene.bodies.at(static_cast<std::size_t>(body));
  const auto* cyl = std::get_if<CylinderShape>(&spec.shape);
  if (cyl == nullptr)
    throw std::invalid_argument("Taylor measures need a cylinder body; '" + spec.name +
                                "' is not one");
  if (cyl->nose.crh > 0.0)
    throw std::invalid_argument("Taylor measures need a flat-ended cylinder; '" + spec.name +
                                "' has a nose");
  return *cyl;
}

double taylor_mean_error(const TaylorMeasures& m, const TaylorReference& ref) {
  return (std::abs(m.length - ref.length) / ref.length +
          std::abs(m.impact_diameter - ref.impact_diameter) / ref.impact_diameter +
          std::abs(m.bulge_diameter - ref.bulge_diameter) / ref.bulge_diameter) /
         3.0;
}

}  // namespace afemp::core
