// Equations of state: the volumetric half of a material. Every EOS here is linear in the
// specific internal energy e, p = a(mu) + b(mu) e with mu = rho / rho0 - 1, which lets the
// energy equation be solved in closed form together with the new pressure (material.hpp).
#pragma once

namespace afemp::core {

struct EosLinearForm {
  double a = 0.0;  // pressure at zero internal energy
  double b = 0.0;  // dp/de at fixed density
};

// No equation of state: pressure follows the hypoelastic law dp = -K tr(d eps), done by the
// composition itself; this type exists so that the variant is never empty.
struct NoEos {};

// Linear EOS: p = K mu.
struct LinearEos {
  double bulk_modulus = 0.0;
  EosLinearForm form(double mu) const;
  double tangent_bulk_modulus(double mu, double e) const;  // rho dp/drho
};

// Mie-Grueneisen with a linear Us-Up Hugoniot, seed 001 eqs 2-21..2-26:
// p = pH (1 - gamma0 mu / 2) + gamma0 rho0 e,  (gamma rho = gamma0 rho0, eq 2-22)
// pH = C1 mu + C2 mu^2 + C3 mu^3 (mu >= 0), pH = C1 mu (mu < 0),
// C1 = rho0 c0^2, C2 = C1 (2s - 1), C3 = C1 (s - 1)(3s - 1).
struct MieGruneisen {
  double rho0 = 0.0, c0 = 0.0, s = 0.0, gamma0 = 0.0;
  EosLinearForm form(double mu) const;
  double tangent_bulk_modulus(double mu, double e) const;
};

// Linear polynomial (LS-DYNA *EOS_LINEAR_POLYNOMIAL):
// p = C0 + C1 mu + C2 mu^2 + C3 mu^3 + (C4 + C5 mu + C6 mu^2) rho0 e,
// with C2 and C6 terms dropped in tension (mu < 0).
struct LinearPolynomialEos {
  double rho0 = 0.0;
  double c[7] = {0, 0, 0, 0, 0, 0, 0};
  EosLinearForm form(double mu) const;
  double tangent_bulk_modulus(double mu, double e) const;
};

}  // namespace afemp::core
