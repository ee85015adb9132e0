// Linear polynomial EOS (LS-DYNA *EOS_LINEAR_POLYNOMIAL, Keyword Manual vol. I):
// p = C0 + C1 mu + C2 mu^2 + C3 mu^3 + (C4 + C5 mu + C6 mu^2) E, E = rho0 e the energy per
// unit reference volume; C2 and C6 are set to zero in tension (mu < 0) as LS-DYNA does.
#include "afemp/equations_of_state.hpp"
#include "core/materials/model_parameters.hpp"

namespace afemp::core {

EosLinearForm LinearPolynomialEos::form(double mu) const {
  const double c2 = mu >= 0.0 ? c[2] : 0.0;
  const double c6 = mu >= 0.0 ? c[6] : 0.0;
  const double a = c[0] + mu * (c[1] + mu * (c2 + mu * c[3]));
  // The composition works with e per unit mass; LS-DYNA's E is per reference volume.
  const double b = (c[4] + mu * (c[5] + mu * c6)) * rho0;
  return {a, b};
}

double LinearPolynomialEos::tangent_bulk_modulus(double mu, double e) const {
  const double c2 = mu >= 0.0 ? c[2] : 0.0;
  const double c6 = mu >= 0.0 ? c[6] : 0.0;
  const double da = c[1] + mu * (2.0 * c2 + 3.0 * c[3] * mu);
  const double db = (c[5] + 2.0 * c6 * mu) * rho0;
  const double k = (1.0 + mu) * (da + db * e);  // rho dp/drho at fixed e
  return k > 0.0 ? k : 0.0;
}

void LinearPolynomialEos::parameters(ParameterVisitor& v) {
  if (v.reading()) rho0 = v.material().density;
  v.require(rho0 > 0.0, "rho0", out_of_range(rho0, "value > 0 (the material's density)"));
  static constexpr std::string_view names[7] = {"C0", "C1", "C2", "C3", "C4", "C5", "C6"};
  for (int i = 0; i < 7; ++i) v.optional(names[i], c[i], 0.0, Range::any());
}

}  // namespace afemp::core
