// uGIMP weights (Bardenhagen & Kober 2004, "The generalized interpolation material point
// method", CMES 5(6), eqs 20-21 for the linear hat): the weight of node I for particle p is
// the hat N_I averaged over the particle's domain, a cube of half-width l_p <= h/2 that keeps
// its initial size ("undeformed" GIMP). Per axis, with r = (x_p - x_I) / h and a = l_p / h:
//
//   |r| <= a            S = 1 - (r^2 + a^2) / (2 a)       dS/dx_p = -r / (a h)
//   a <= |r| <= 1 - a   S = 1 - |r|                       dS/dx_p = -sign(r) / h
//   1 - a <= |r| < 1+a  S = (1 + a - |r|)^2 / (4 a)       dS/dx_p = -sign(r) (1 + a - |r|) / (2 a
//   h)
//
// S and its gradient are continuous (the linear hat's gradient jumps at every cell face),
// and near the edge of a node's support the weight fades as the square of the overlap
// while its gradient fades linearly: |dS|^2 / S stays bounded, so a node that a particle
// barely reaches gets a small mass and a small force together. Each particle reaches at most
// three nodes per axis: base, base + 1, base + 2 with base = floor(x / h - 1/2).
#pragma once

#include <array>
#include <cmath>

#include "core/grid/tensor_weights.hpp"

namespace afemp::core {

// Weights of the three nodes base..base+2 along one axis.
using GimpAxis = AxisWeights<3>;

// xi = (x_p - origin) / h, a = l_p / h in (0, 1/2], h the cell size.
inline GimpAxis gimp_axis(double xi, double a, double h) {
  GimpAxis out;
  out.base = static_cast<int>(std::floor(xi - 0.5));
  const double inv_h = 1.0 / h;
  double moment = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double r = xi - (out.base + k);
    const double ar = std::abs(r);
    const double sign = r < 0.0 ? -1.0 : 1.0;
    double w = 0.0, g = 0.0;
    if (ar <= a) {
      w = 1.0 - (r * r + a * a) / (2.0 * a);
      g = -r / a;
    } else if (ar <= 1.0 - a) {
      w = 1.0 - ar;
      g = -sign;
    } else if (ar < 1.0 + a) {
      const double t = 1.0 + a - ar;
      w = t * t / (4.0 * a);
      g = -sign * t / (2.0 * a);
    }
    const auto kk = static_cast<std::size_t>(k);
    out.w[kk] = w;
    out.grad[kk] = g * inv_h;
    out.offset[kk] = -r * h;
    moment += w * r * r;
  }
  // sum S (x_I - x_p)^2 >= a^2 h^2 / 3 (the particle's own spread): never singular.
  out.inverse_moment = 1.0 / (moment * h * h);
  return out;
}

}  // namespace afemp::core
