// Compressible neo-Hookean solid (afemp/neo_hookean.hpp). The split form: with
// W = mu / 2 (I1 J^(-2/3) - 3) + K / 2 (J - 1)^2 (the mixed u-p TLMPM paper, Zhang et al. 2022,
// eqs 15-16; I3^(-1/3) = J^(-2/3)), the Kirchhoff stress is tau = mu J^(-2/3) dev(B)
// + K J (J - 1) I (Simo & Hughes 1998, their isochoric split; docs/references.md), and the
// Cauchy stress sigma = tau / J. The log form: W = mu / 2 (I1 - 3) - mu ln J
// + lambda / 2 (ln J)^2 gives tau = mu (B - I) + lambda ln J I (Bonet & Wood 2008, the
// compressible neo-Hookean solid; docs/references.md), as MPM3D-F90's neoh (Constitution.f90).
#include "afemp/neo_hookean.hpp"

#include <cmath>

#include "core/materials/material.hpp"

namespace afemp::core {

PointUpdate NeoHookean::update_point(const Material& material, const NoEos&, PointState& point,
                                     const SymTensor& d_eps, double) const {
  const Mat3& f = *point.deformation_gradient;
  const double j = determinant(f);
  // B = F F^T.
  auto row_dot = [&](int a, int b) {
    return f.m[a][0] * f.m[b][0] + f.m[a][1] * f.m[b][1] + f.m[a][2] * f.m[b][2];
  };
  const SymTensor b{row_dot(0, 0), row_dot(1, 1), row_dot(2, 2),
                    row_dot(1, 2), row_dot(0, 2), row_dot(0, 1)};
  const double mu = material.shear_modulus(), k = material.bulk_modulus();
  // As in constitutive_update: work per unit mass over the volume the increment acts on.
  const double inv_rho_work = 1.0 / (point.density * (1.0 + d_eps.trace()));
  const SymTensor stress_old = point.stress;
  if (form == Form::log) {
    // Bonet & Wood's form: sigma = (mu (B - I) + lambda ln J I) / J.
    const double lambda = k - 2.0 / 3.0 * mu, ln_j = std::log(j);
    point.stress = (1.0 / j) * (mu * b + (lambda * ln_j - mu) * SymTensor::identity());
  } else {
    // The mixed u-p MPM's projected pressure replaces K (J - 1) where it is on (eq 17 there).
    const double p = point.mixed_pressure ? *point.mixed_pressure : k * (j - 1.0);
    point.stress = (mu * std::pow(j, -5.0 / 3.0)) * b.deviator() + p * SymTensor::identity();
  }
  point.energy += 0.5 * double_dot(stress_old + point.stress, d_eps) * inv_rho_work;
  return {};
}

void NeoHookean::parameters(ParameterVisitor& v) {
  std::size_t f = static_cast<std::size_t>(form);
  v.choice("form", f, form_names, std::size_t{0});
  form = static_cast<Form>(f);
}

}  // namespace afemp::core
