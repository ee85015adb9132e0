// Compressible Mooney-Rivlin solid (afemp/mooney_rivlin.hpp). With the isochoric split
// Bbar = J^(-2/3) F F^T and W = W(I1bar, I2bar) + K / 2 (J - 1)^2, the Kirchhoff stress is
// tau = 2 dev[(W_1 + I1bar W_2) Bbar - W_2 Bbar^2] + K J (J - 1) I (Holzapfel 2000, the
// isochoric split; docs/references.md), with W_1 = C10 and W_2 = C01 here, and sigma = tau / J.
#include "afemp/mooney_rivlin.hpp"

#include <cmath>
#include <cstdio>

#include "core/materials/material.hpp"

namespace afemp::core {

PointUpdate MooneyRivlin::update_point(const Material& material, const NoEos&, PointState& point,
                                       const SymTensor& d_eps, double) const {
  const Mat3& f = *point.deformation_gradient;
  const double j = determinant(f);
  const double s = std::pow(j, -2.0 / 3.0);
  auto row_dot = [&](int a, int b) {
    return s * (f.m[a][0] * f.m[b][0] + f.m[a][1] * f.m[b][1] + f.m[a][2] * f.m[b][2]);
  };
  // Bbar and Bbar^2 (symmetric).
  const SymTensor b{row_dot(0, 0), row_dot(1, 1), row_dot(2, 2),
                    row_dot(1, 2), row_dot(0, 2), row_dot(0, 1)};
  const SymTensor b2{
      b.xx * b.xx + b.xy * b.xy + b.xz * b.xz, b.xy * b.xy + b.yy * b.yy + b.yz * b.yz,
      b.xz * b.xz + b.yz * b.yz + b.zz * b.zz, b.xy * b.xz + b.yy * b.yz + b.yz * b.zz,
      b.xx * b.xz + b.xy * b.yz + b.xz * b.zz, b.xx * b.xy + b.xy * b.yy + b.xz * b.yz};
  const double i1 = b.trace();
  const SymTensor tau = (2.0 * (c10 + i1 * c01)) * b - (2.0 * c01) * b2;
  const double k = material.bulk_modulus();
  const double inv_rho_work = 1.0 / (point.density * (1.0 + d_eps.trace()));
  const SymTensor stress_old = point.stress;
  // The mixed u-p MPM's projected pressure replaces K (J - 1) where it is on.
  const double p = point.mixed_pressure ? *point.mixed_pressure : k * (j - 1.0);
  point.stress = (1.0 / j) * tau.deviator() + p * SymTensor::identity();
  point.energy += 0.5 * double_dot(stress_old + point.stress, d_eps) * inv_rho_work;
  return {};
}

void MooneyRivlin::parameters(ParameterVisitor& v) {
  v.required("C10", c10, Range::positive());
  v.required("C01", c01, Range::non_negative());
  // The small-strain shear modulus 2 (C10 + C01) is the material's G = 3 K E / (9 K - E).
  const MaterialConstants& m = v.material();
  const double g =
      3.0 * m.bulk_modulus * m.youngs_modulus / (9.0 * m.bulk_modulus - m.youngs_modulus);
  const double mu = 2.0 * (c10 + c01);
  const double nu = (3.0 * m.bulk_modulus - m.youngs_modulus) / (6.0 * m.bulk_modulus);
  char why[320];
  std::snprintf(why, sizeof why,
                "2 (C10 + C01) = %.9g is the solid's shear modulus and must equal the material's "
                "G = E / (2 (1 + nu)) = %.9g; with nu = %.9g set E = %.9g",
                mu, g, nu, 2.0 * (1.0 + nu) * mu);
  v.require(std::abs(mu - g) <= 1e-6 * g, "C10", why);
}

}  // namespace afemp::core
