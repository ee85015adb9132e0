// Mie-Grueneisen EOS with a linear Us-Up Hugoniot in the cubic form of seed 001 eqs 2-21..2-26:
// p = pH (1 - gamma0 mu / 2) + gamma0 rho0 e, pH = C1 mu + C2 mu^2 + C3 mu^3 (mu >= 0),
// pH = C1 mu (mu < 0), C1 = rho0 c0^2, C2 = C1 (2s - 1), C3 = C1 (s - 1)(3s - 1).
#include "core/materials/equations_of_state.hpp"

namespace afemp::core {

// mu is NOT clamped in expansion: the cubic Hugoniot has no pole (unlike the rational form
// rho0 c0^2 mu (1 + mu) / (1 - (s - 1) mu)^2, which needs a compression cutoff), and in
// tension pH = C1 mu stays finite for every mu > -1 with dp/dmu = C1 (1 - gamma0 mu) > 0.
// Limiting the tensile pressure is a spall/failure criterion's job, not the EOS's.

EosLinearForm MieGruneisen::form(double mu) const {
  const double c1 = rho0 * c0 * c0;
  double p_hugoniot;
  if (mu >= 0.0) {
    const double c2 = c1 * (2.0 * s - 1.0);
    const double c3 = c1 * (s - 1.0) * (3.0 * s - 1.0);
    p_hugoniot = mu * (c1 + mu * (c2 + mu * c3));
  } else {
    p_hugoniot = c1 * mu;
  }
  // gamma rho = gamma0 rho0 (eq 2-22) makes the energy coefficient constant.
  return {p_hugoniot * (1.0 - 0.5 * gamma0 * mu), gamma0 * rho0};
}

double MieGruneisen::tangent_bulk_modulus(double mu, double /*e*/) const {
  // b = gamma0 rho0 is independent of mu, so only a(mu) contributes to dp/dmu at fixed e.
  const double c1 = rho0 * c0 * c0;
  double dp_dmu;
  if (mu >= 0.0) {
    const double c2 = c1 * (2.0 * s - 1.0);
    const double c3 = c1 * (s - 1.0) * (3.0 * s - 1.0);
    const double p_hugoniot = mu * (c1 + mu * (c2 + mu * c3));
    const double dp_hugoniot = c1 + mu * (2.0 * c2 + 3.0 * c3 * mu);
    dp_dmu = dp_hugoniot * (1.0 - 0.5 * gamma0 * mu) - 0.5 * gamma0 * p_hugoniot;
  } else {
    dp_dmu = c1 * (1.0 - gamma0 * mu);
  }
  const double k = (1.0 + mu) * dp_dmu;  // rho dp/drho with rho = rho0 (1 + mu)
  return k > 0.0 ? k : 0.0;
}

}  // namespace afemp::core
