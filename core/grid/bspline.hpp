// B-spline weights (Steffen, Kirby & Berzins 2008, "Analysis and reduction of quadrature errors
// in the material point method (MPM)", IJNME 76(6), §3: the quadratic and cubic B-splines
// centred on the grid nodes). With xi = (x_p - origin) / h and r = xi - I the distance to node
// I in cells, the interior functions are
//
//   quadratic  |r| < 1/2         S = 3/4 - r^2
//              1/2 <= |r| < 3/2  S = (3/2 - |r|)^2 / 2
//   cubic      |r| < 1           S = 2/3 - r^2 + |r|^3 / 2
//              1 <= |r| < 2      S = (2 - |r|)^3 / 6
//
// C1 (quadratic) and C2 (cubic) across cell faces, so a particle crossing a face sees no jump
// in its gradient, the cause of the linear hat's cell-crossing noise. A particle reaches 3
// (4) nodes per axis: base = floor(xi - 1/2) (floor(xi) - 1) .. base + Order.
//
// Boundary-modified bases (de Vaucorbeil, Nguyen, Nezamabadi & Hutchinson 2020, "Material point
// method after 25 years", Adv. Appl. Mech. 53, §3.3): the grid's faces bound the basis, so no
// node beyond a face takes a weight. Next to the lower face (node 0; the upper face is its
// mirror image, xi -> cells - xi) the first functions change:
//
//   quadratic  xi < 1/2:  S_0 = 1 - xi, S_1 = xi                       (the hat on that half cell)
//   cubic      xi < 1:    S_0 = 1 - xi + xi^3 / 6,  S_1 = 2/3 - u^2 + u^3 / 3 with u = 1 - xi,
//                         S_2 = xi^3 / 6
//
// They keep the partition of unity and the linear fields (sum S = 1, sum S x_I = x_p: an
// affine velocity field and a uniform stress stay exact up to the face), their continuity
// class, and S_0 = 1 on the face, so a condition set on the face's nodes holds at the face.
#pragma once

#include <cmath>
#include <utility>

#include "core/grid/tensor_weights.hpp"

namespace afemp::core {

namespace spline_detail {

// Weights and derivatives (per cell) of nodes base..base+2 at xi, lower face modified.
inline void quadratic(double xi, int& base, double* w, double* d) {
  base = static_cast<int>(std::floor(xi - 0.5));
  if (base < 0) {  // xi < 1/2: nodes -1 (none), 0, 1
    w[0] = 0.0, w[1] = 1.0 - xi, w[2] = xi;
    d[0] = 0.0, d[1] = -1.0, d[2] = 1.0;
    return;
  }
  const double f = xi - 0.5 - base;  // in [0, 1)
  const double g = 1.0 - f;
  w[0] = 0.5 * g * g, w[1] = 0.75 - (f - 0.5) * (f - 0.5), w[2] = 0.5 * f * f;
  d[0] = -g, d[1] = 1.0 - 2.0 * f, d[2] = f;
}

// Weights and derivatives (per cell) of nodes base..base+3 at xi, lower face modified.
inline void cubic(double xi, int& base, double* w, double* d) {
  const int c = static_cast<int>(std::floor(xi));
  base = c - 1;
  const double f = xi - c, g = 1.0 - f;
  if (c <= 0) {  // the face cell: nodes -1 (none), 0, 1, 2
    w[0] = 0.0, d[0] = 0.0;
    w[1] = 1.0 - f + f * f * f / 6.0, d[1] = -1.0 + 0.5 * f * f;
    w[2] = 2.0 / 3.0 - g * g + g * g * g / 3.0, d[2] = 2.0 * g - g * g;
    w[3] = f * f * f / 6.0, d[3] = 0.5 * f * f;
    return;
  }
  w[0] = g * g * g / 6.0, d[0] = -0.5 * g * g;
  w[1] = 2.0 / 3.0 - f * f + 0.5 * f * f * f, d[1] = -2.0 * f + 1.5 * f * f;
  w[2] = 2.0 / 3.0 - g * g + 0.5 * g * g * g, d[2] = 2.0 * g - 1.5 * g * g;
  w[3] = f * f * f / 6.0, d[3] = 0.5 * f * f;
}

}  // namespace spline_detail

// Fewest cells per axis each order needs: with fewer, every cell is a face cell and the basis
// is no longer the B-spline.
constexpr int bspline_min_cells(int order) {
  return order;
}

// Weights of nodes base..base+Order along one axis: xi = (x_p - origin) / h in [0, cells],
// h the cell size (Order 2 or 3).
template <int Order>
AxisWeights<Order + 1> bspline_axis(double xi, int cells, double h) {
  constexpr int span = Order + 1;
  AxisWeights<span> out;
  double w[span], d[span];
  // Past the middle the upper face is the nearer one: evaluate the mirror image, whose lower
  // face is the upper face, and turn it back (weights reversed, derivatives negated).
  const bool upper = xi > 0.5 * cells;
  int base = 0;
  if constexpr (Order == 2)
    spline_detail::quadratic(upper ? cells - xi : xi, base, w, d);
  else
    spline_detail::cubic(upper ? cells - xi : xi, base, w, d);
  if (upper) {
    base = cells - (base + Order);
    for (int k = 0; k < span / 2; ++k) {
      std::swap(w[k], w[span - 1 - k]);
      std::swap(d[k], d[span - 1 - k]);
    }
    for (double& v : d) v = -v;
  }
  out.base = base;
  const double inv_h = 1.0 / h;
  double moment = 0.0;
  for (int k = 0; k < span; ++k) {
    const double r = xi - (base + k);
    const auto kk = static_cast<std::size_t>(k);
    out.w[kk] = w[k];
    out.grad[kk] = d[k] * inv_h;
    out.offset[kk] = -r * h;
    moment += w[k] * r * r;
  }
  // sum S (x_I - x_p)^2: h^2 / 4 (quadratic) or h^2 / 3 (cubic) inside, and at least
  // xi (1 - xi) h^2 > 0 within the face's half cell; on the face itself a particle sits on
  // its node and the moment is 0: its affine velocity is then not defined (stencil.hpp).
  out.inverse_moment = moment > 0.0 ? 1.0 / (moment * h * h) : 0.0;
  return out;
}

}  // namespace afemp::core
