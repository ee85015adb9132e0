// Jones-Wilkins-Lee EOS of detonation products: E. L. Lee, H. C. Hornig and J. W. Kury,
// "Adiabatic expansion of high explosive detonation products", UCRL-50422 (1968); the form of
// LS-DYNA's *EOS_JWL (E per unit reference volume). R. Menikoff, "JWL equation of state",
// LA-UR-15-29536 (2017), derives its properties.
#include <cmath>

#include "afemp/equations_of_state.hpp"

namespace afemp::core {

double Jwl::pressure(double V, double E) const {
  return A * (1.0 - omega / (R1 * V)) * std::exp(-R1 * V) +
         B * (1.0 - omega / (R2 * V)) * std::exp(-R2 * V) + omega * E / V;
}

EosLinearForm Jwl::form(double mu) const {
  const double V = 1.0 / (1.0 + mu);
  const double a = A * (1.0 - omega / (R1 * V)) * std::exp(-R1 * V) +
                   B * (1.0 - omega / (R2 * V)) * std::exp(-R2 * V);
  // omega E / V with E = rho0 e: b = omega rho0 / V.
  return {a, omega * rho0 / V};
}

double Jwl::tangent_bulk_modulus(double mu, double e) const {
  // rho dp/drho = -V dp/dV at fixed e.
  const double V = 1.0 / (1.0 + mu);
  const double e1 = std::exp(-R1 * V), e2 = std::exp(-R2 * V);
  const double da = A * e1 * (omega / (R1 * V * V) - R1 + omega / V) +
                    B * e2 * (omega / (R2 * V * V) - R2 + omega / V);
  const double db = -omega * rho0 / (V * V);
  const double k = -V * (da + db * e);
  return k > 0.0 ? k : 0.0;
}

}  // namespace afemp::core
