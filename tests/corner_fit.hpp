// A point's displacement read from particles as the V8 harnesses read a corner's: the component
// u = a + b . (X - X_c) fitted by least squares to the particles whose reference position X lies
// within a radius of X_c (in its first D coordinates: the plane of a plane-strain panel, or
// space), a being the value at X_c. A fit, not the nearest particle, because no particle sits at
// a corner: the nearest lies a quarter of a cell inside. Shared by tests/cooks_membrane.hpp and
// tests/twisting_column.hpp.
#pragma once

#include <cstddef>

#include "afemp/tensor.hpp"
#include "mpm/particles.hpp"

namespace afemp::test {

// `component` is 0, 1 or 2 (x, y, z).
template <int D>
double fitted_displacement(const mpm::Particles& q, const core::Vec3& at, double radius,
                           int component) {
  constexpr int n = D + 1;
  double normal[n][n] = {}, rhs[n] = {};
  for (std::size_t i = 0; i < q.size(); ++i) {
    const core::Vec3 d = q.reference_position[i] - at;
    double row[n] = {1.0}, distance2 = 0.0;
    for (int a = 0; a < D; ++a) {
      row[a + 1] = d[a];
      distance2 += d[a] * d[a];
    }
    if (distance2 > radius * radius) continue;
    const double u = q.position[i][component] - q.reference_position[i][component];
    for (int a = 0; a < n; ++a) {
      rhs[a] += row[a] * u;
      for (int b = 0; b < n; ++b) normal[a][b] += row[a] * row[b];
    }
  }
  // Gaussian elimination (the normal matrix is symmetric positive definite).
  for (int k = 0; k < n; ++k)
    for (int r = k + 1; r < n; ++r) {
      const double f = normal[r][k] / normal[k][k];
      for (int c = k; c < n; ++c) normal[r][c] -= f * normal[k][c];
      rhs[r] -= f * rhs[k];
    }
  double x[n];
  for (int k = n - 1; k >= 0; --k) {
    double s = rhs[k];
    for (int c = k + 1; c < n; ++c) s -= normal[k][c] * x[c];
    x[k] = s / normal[k][k];
  }
  return x[0];
}

}  // namespace afemp::test
