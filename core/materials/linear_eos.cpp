// Linear equation of state p = K mu, mu = rho / rho0 - 1: the bulk half of small-strain
// elasticity written in terms of density, with no energy dependence (b = 0).
#include "afemp/equations_of_state.hpp"
#include "core/materials/model_parameters.hpp"

namespace afemp::core {

EosLinearForm LinearEos::form(double mu) const {
  return {bulk_modulus * mu, 0.0};
}

double LinearEos::tangent_bulk_modulus(double mu, double /*e*/) const {
  // rho dp/drho = (1 + mu) dp/dmu; clamped so a (nonphysical) mu < -1 gives no imaginary speed.
  const double k = (1.0 + mu) * bulk_modulus;
  return k > 0.0 ? k : 0.0;
}

void LinearEos::parameters(ParameterVisitor& v) {
  v.optional("bulk_modulus", bulk_modulus, v.material().bulk_modulus, Range::positive());
}

}  // namespace afemp::core
