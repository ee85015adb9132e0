// Tangent-ogive nose geometry (core/ogive_nose.hpp): the arc r(t) = sqrt(S^2 - t^2) - (S - R),
// S = 2 psi R, cut by a meplat of diameter 2a at t_a = sqrt(S^2 - (S - R + a)^2).
#include "afemp/ogive_nose.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace afemp::core {

double ogive_nose_length(const OgiveNose& nose, double radius) {
  const double s = 2.0 * nose.crh * radius, c = s - radius + 0.5 * nose.meplat;
  return std::sqrt(std::max(0.0, s * s - c * c));
}

double ogive_radius(const OgiveNose& nose, double radius, double t) {
  const double s = 2.0 * nose.crh * radius;
  const double tt = std::clamp(t, 0.0, ogive_nose_length(nose, radius));
  return std::max(0.5 * nose.meplat, std::sqrt(std::max(0.0, s * s - tt * tt)) - (s - radius));
}

double ogive_nose_volume(const OgiveNose& nose, double radius) {
  // r^2 = S^2 + c^2 - t^2 - 2 c sqrt(S^2 - t^2), c = S - R; the integral of sqrt(S^2 - t^2) is
  // (t sqrt(S^2 - t^2) + S^2 asin(t / S)) / 2.
  const double s = 2.0 * nose.crh * radius, c = s - radius;
  const double t = ogive_nose_length(nose, radius);
  const double root = std::sqrt(std::max(0.0, s * s - t * t));
  const double arc = 0.5 * (t * root + s * s * std::asin(std::min(1.0, t / s)));
  return std::numbers::pi * ((s * s + c * c) * t - t * t * t / 3.0 - 2.0 * c * arc);
}

}  // namespace afemp::core
