// Programmed burn: lighting times and burn fractions (core/programmed_burn.hpp).
#include "core/programmed_burn.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace afemp::core {

Vec3 nearest_point(const DetonationSpec& d, const Vec3& x) {
  switch (d.kind) {
    case DetonationSpec::Kind::point:
      return d.point;
    case DetonationSpec::Kind::plane:
      return x - dot(x - d.point, d.normal) * d.normal;
    case DetonationSpec::Kind::line: {
      const Vec3 axis = d.end - d.point;
      const double length2 = dot(axis, axis);
      const double s = length2 > 0.0 ? std::clamp(dot(x - d.point, axis) / length2, 0.0, 1.0) : 0.0;
      return d.point + s * axis;
    }
  }
  return d.point;
}

double lighting_time(const Vec3& x, std::span<const DetonationSpec> detonations, double D) {
  double t = std::numeric_limits<double>::infinity();
  for (const DetonationSpec& d : detonations)
    if (!d.shadow) t = std::min(t, d.time + norm(x - nearest_point(d, x)) / D);
  return t;
}

double burn_fraction(const ProgrammedBurn& burn, double rho0, double previous, double t,
                     double t_light, double length, double V) {
  double f = previous;
  const double D = burn.detonation_velocity;
  if (burn.lighting_time && t > t_light) f = std::max(f, 2.0 * (t - t_light) * D / (3.0 * length));
  if (burn.volumetric) f = std::max(f, (1.0 - V) / (1.0 - burn.cj_volume(rho0)));
  return std::min(f, 1.0);
}

}  // namespace afemp::core
