// Jones-Wilkins-Lee EOS of detonation products: E. L. Lee, H. C. Hornig and J. W. Kury,
// "Adiabatic expansion of high explosive detonation products", UCRL-50422 (1968); the form of
// LS-DYNA's *EOS_JWL (E per unit reference volume). R. Menikoff, "JWL equation of state",
// LA-UR-15-29536 (2017), derives its properties.
#include <cmath>

#include "afemp/equations_of_state.hpp"
#include "core/materials/model_parameters.hpp"

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

void Jwl::parameters(ParameterVisitor& v) {
  if (v.reading()) rho0 = v.material().density;
  v.require(rho0 > 0.0, "rho0", out_of_range(rho0, "value > 0 (the material's density)"));
  v.required("A", A, Range::positive());
  v.required("B", B, Range::positive());
  v.required("R1", R1, Range::positive());
  v.required("R2", R2, Range::positive());
  v.required("omega", omega, Range::positive());
  v.required("E0", E0, Range::non_negative());
  v.require(B < A, "B", out_of_range(B, "value < A (detonation products)"));
  v.require(R1 > R2, "R1", out_of_range(R1, "value > R2"));
  // The products at the reference volume with the detonation energy must push: a negative
  // pressure there is a set of parameters in another unit system, or mistyped.
  const double p1 = pressure(1.0, E0);
  v.require(p1 > 0.0, "E0",
            "eos pressure at V = 1 and E = E0 is " + format_value(p1) +
                ", must be > 0 (check A, B, R1, R2, omega and E0 and their units)");
}

}  // namespace afemp::core
