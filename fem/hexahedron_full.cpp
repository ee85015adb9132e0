// Fully integrated hexahedron with B-bar dilatation (Hughes 1980): Gauss-point gradients,
// B-bar velocity gradient and the consistent nodal forces (fem/hexahedron_full.hpp).
#include "fem/hexahedron_full.hpp"

#include <algorithm>
#include <cmath>

namespace afemp::fem {

FullHex full_hex(const HexVectors& x) {
  core::Vec3 centroid;
  for (const core::Vec3& p : x) centroid += p;
  centroid *= 0.125;
  HexVectors c;  // relative to the centroid: J is unchanged, its round-off smaller
  for (int a = 0; a < 8; ++a) c[a] = x[a] - centroid;

  const double r = 1.0 / std::sqrt(3.0);
  FullHex e;
  e.mean_grad.fill(core::Vec3{});
  for (int g = 0; g < 8; ++g) {
    const double xi = r * kHexNatural[g][0], eta = r * kHexNatural[g][1],
                 zeta = r * kHexNatural[g][2];
    double dn[8][3];        // dN_a / d(xi, eta, zeta)
    double jac[3][3] = {};  // J_ij = dx_i / dxi_j
    for (int a = 0; a < 8; ++a) {
      const double sx = kHexNatural[a][0], sy = kHexNatural[a][1], sz = kHexNatural[a][2];
      dn[a][0] = 0.125 * sx * (1.0 + sy * eta) * (1.0 + sz * zeta);
      dn[a][1] = 0.125 * sy * (1.0 + sx * xi) * (1.0 + sz * zeta);
      dn[a][2] = 0.125 * sz * (1.0 + sx * xi) * (1.0 + sy * eta);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) jac[i][j] += c[a][i] * dn[a][j];
    }
    // Cofactors: (J^-1)_kj = cof_jk / det J, so det J grad N_a = cof dN_a/dxi needs no division.
    const double cof[3][3] = {{jac[1][1] * jac[2][2] - jac[1][2] * jac[2][1],
                               jac[1][2] * jac[2][0] - jac[1][0] * jac[2][2],
                               jac[1][0] * jac[2][1] - jac[1][1] * jac[2][0]},
                              {jac[0][2] * jac[2][1] - jac[0][1] * jac[2][2],
                               jac[0][0] * jac[2][2] - jac[0][2] * jac[2][0],
                               jac[0][1] * jac[2][0] - jac[0][0] * jac[2][1]},
                              {jac[0][1] * jac[1][2] - jac[0][2] * jac[1][1],
                               jac[0][2] * jac[1][0] - jac[0][0] * jac[1][2],
                               jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0]}};
    const double det = jac[0][0] * cof[0][0] + jac[0][1] * cof[0][1] + jac[0][2] * cof[0][2];
    e.weight[g] = det;
    const double inv_det = 1.0 / det;
    for (int a = 0; a < 8; ++a) {
      core::Vec3 det_grad;
      for (int j = 0; j < 3; ++j)
        det_grad[j] = cof[j][0] * dn[a][0] + cof[j][1] * dn[a][1] + cof[j][2] * dn[a][2];
      e.mean_grad[a] += det_grad;
      e.grad[g][a] = inv_det * det_grad;
    }
  }
  double volume = 0.0;
  for (double w : e.weight) volume += w;
  e.volume = volume;
  for (core::Vec3& m : e.mean_grad) m *= 1.0 / volume;
  return e;
}

double min_jacobian(const FullHex& e) {
  return *std::min_element(e.weight.begin(), e.weight.end());
}

core::Mat3 velocity_gradient_bbar(const FullHex& e, int g, const HexVectors& v) {
  core::Mat3 l;
  double mean_trace = 0.0;
  for (int a = 0; a < 8; ++a) {
    const core::Vec3& dn = e.grad[g][a];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) l.m[i][j] += v[a][i] * dn[j];
    mean_trace += core::dot(v[a], e.mean_grad[a]);
  }
  const double shift = (mean_trace - (l.m[0][0] + l.m[1][1] + l.m[2][2])) / 3.0;
  for (int i = 0; i < 3; ++i) l.m[i][i] += shift;
  return l;
}

void add_stress_forces_bbar(const FullHex& e, const std::array<core::SymTensor, 8>& sigma,
                            HexVectors& f) {
  double pressure_integral = 0.0;  // integral of the mean stress, carried by the mean gradient
  for (int g = 0; g < 8; ++g) {
    const double w = e.weight[g];
    pressure_integral += w * sigma[g].mean();
    const core::SymTensor s = w * sigma[g].deviator();
    for (int a = 0; a < 8; ++a) {
      const core::Vec3& b = e.grad[g][a];
      f[a].x -= s.xx * b.x + s.xy * b.y + s.xz * b.z;
      f[a].y -= s.xy * b.x + s.yy * b.y + s.yz * b.z;
      f[a].z -= s.xz * b.x + s.yz * b.y + s.zz * b.z;
    }
  }
  for (int a = 0; a < 8; ++a) f[a] -= pressure_integral * e.mean_grad[a];
}

}  // namespace afemp::fem
