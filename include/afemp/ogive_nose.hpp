// The tangent-ogive nose of a projectile, the usual penetrator shape (Forrestal's and
// Hanchak's 3.0-caliber-radius-head rods). A nose of caliber-radius-head psi (CRH) on a shank
// of radius R is the arc of radius S = 2 psi R, tangent to the shank where the nose starts;
// at distance t from that start the radius is
//   r(t) = sqrt(S^2 - t^2) - (S - R),
// and the arc meets the axis at L = sqrt(S^2 - (S - R)^2) = R sqrt(4 psi - 1). A meplat (a flat
// tip of diameter 2a) cuts the arc where r = a, at t_a = sqrt(S^2 - (S - R + a)^2). psi = 0.5
// is a hemisphere. The nose volume, pi times the integral of r^2 from 0 to t_a, is in closed
// form (ogive_nose_volume), which the shape tests use.
#pragma once

namespace afemp::core {

/// A tangent-ogive nose on a cylinder body (CylinderShape::nose).
struct OgiveNose {
  double crh = 0.0;     ///< caliber-radius-head psi >= 0.5; 0: no nose (a flat end)
  double meplat = 0.0;  ///< diameter of the flat tip, 0 <= meplat < 2R
};

/// Length of the nose (t_a above) on a shank of radius `radius`.
double ogive_nose_length(const OgiveNose& nose, double radius);
/// r(t) for 0 <= t <= nose length: radius at distance t from the start of the nose.
double ogive_radius(const OgiveNose& nose, double radius, double t);
/// pi times the integral of r(t)^2 over the nose.
double ogive_nose_volume(const OgiveNose& nose, double radius);

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::OgiveNose;
}  // namespace afemp
