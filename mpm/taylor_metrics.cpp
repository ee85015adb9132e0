#include "mpm/taylor_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace afemp::mpm {

TaylorMeasures measure_taylor(const Particles& p, const core::Scene& scene, int body) {
  const core::BodySpec& spec = scene.bodies.at(static_cast<std::size_t>(body));
  const auto* cyl = std::get_if<core::CylinderShape>(&spec.shape);
  if (cyl == nullptr)
    throw std::invalid_argument("Taylor measures need a cylinder body; '" + spec.name +
                                "' is not one");
  const Vec3 axis = (1.0 / core::norm(cyl->axis)) * cyl->axis;
  auto axial = [&](std::size_t i) { return core::dot(p.position[i] - cyl->base, axis); };
  auto radial = [&](std::size_t i) {
    const Vec3 d = p.position[i] - cyl->base;
    return core::norm(d - core::dot(d, axis) * axis);
  };
  auto half = [&](std::size_t i) { return 0.5 * std::cbrt(p.volume[i]); };

  double lo = 1e300, hi = -1e300, spacing = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != body) continue;
    lo = std::min(lo, axial(i) - half(i));
    hi = std::max(hi, axial(i) + half(i));
    spacing = std::max(spacing, 2.0 * half(i));
  }
  if (hi < lo) throw std::invalid_argument("body '" + spec.name + "' has no particles");
  // The wall end: the end nearer the cylinder base (the base sits on the wall).
  const double station = lo + 0.2 * cyl->length;
  double r_face = 0.0, r_bulge = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.body[i] != body) continue;
    const double a = axial(i), r = radial(i) + half(i);
    if (a - half(i) <= lo + 0.5 * spacing) r_face = std::max(r_face, r);
    if (std::abs(a - station) <= 0.5 * spacing) r_bulge = std::max(r_bulge, r);
  }
  return {hi - lo, 2.0 * r_face, 2.0 * r_bulge};
}

double taylor_mean_error(const TaylorMeasures& m, const core::TaylorReference& ref) {
  return (std::abs(m.length - ref.length) / ref.length +
          std::abs(m.impact_diameter - ref.impact_diameter) / ref.impact_diameter +
          std::abs(m.bulge_diameter - ref.bulge_diameter) / ref.bulge_diameter) /
         3.0;
}

}  // namespace afemp::mpm
