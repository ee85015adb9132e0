// F of a trilinear hexahedron and its F-bar form (fem/hexahedron_deformation_gradient.hpp;
// de Souza Neto, Peric, Dutko & Owen, "Design of simple low order finite elements for large
// strain analysis of nearly incompressible solids", IJSS 33 (1996) 3277-3296).
#include "fem/hexahedron_deformation_gradient.hpp"

#include <cmath>

namespace afemp::fem {

namespace {
// d(sum_a N_a y_a) / d(xi, eta, zeta), column j the derivative along natural axis j.
core::Mat3 natural_jacobian(const HexVectors& y, double xi, double eta, double zeta) {
  core::Mat3 jac;
  for (int a = 0; a < 8; ++a) {
    const double* n = kHexNatural[a];
    const double fx = 1.0 + n[0] * xi, fy = 1.0 + n[1] * eta, fz = 1.0 + n[2] * zeta;
    const core::Vec3 g{0.125 * n[0] * fy * fz, 0.125 * n[1] * fx * fz, 0.125 * n[2] * fx * fy};
    core::add_outer(jac, y[static_cast<std::size_t>(a)], g);
  }
  return jac;
}
}  // namespace

core::Mat3 hexahedron_deformation_gradient(const HexVectors& x, const HexVectors& x0, double xi,
                                           double eta, double zeta) {
  const core::Mat3 jx = natural_jacobian(x, xi, eta, zeta);
  const core::Mat3 j0 = natural_jacobian(x0, xi, eta, zeta);
  // (dX/dxi)^(-1) by its adjugate.
  const auto& a = j0.m;
  core::Mat3 inv;
  inv.m[0][0] = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  inv.m[0][1] = a[0][2] * a[2][1] - a[0][1] * a[2][2];
  inv.m[0][2] = a[0][1] * a[1][2] - a[0][2] * a[1][1];
  inv.m[1][0] = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  inv.m[1][1] = a[0][0] * a[2][2] - a[0][2] * a[2][0];
  inv.m[1][2] = a[0][2] * a[1][0] - a[0][0] * a[1][2];
  inv.m[2][0] = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  inv.m[2][1] = a[0][1] * a[2][0] - a[0][0] * a[2][1];
  inv.m[2][2] = a[0][0] * a[1][1] - a[0][1] * a[1][0];
  const double inv_det = 1.0 / core::determinant(j0);
  core::Mat3 f;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double s = 0.0;
      for (int k = 0; k < 3; ++k) s += jx.m[i][k] * inv.m[k][j];
      f.m[i][j] = s * inv_det;
    }
  return f;
}

core::Mat3 f_bar(const core::Mat3& f, double j_bar) {
  const double scale = std::cbrt(j_bar / core::determinant(f));
  core::Mat3 out;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.m[i][j] = scale * f.m[i][j];
  return out;
}

}  // namespace afemp::fem
