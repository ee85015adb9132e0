// The Johnson-Holmquist ceramic model, JH-2: Johnson & Holmquist (1994), "An improved
// computational constitutive model for brittle materials", High-Pressure Science and
// Technology 1993, AIP Conf. Proc. 309, pp. 981-984 (LS-DYNA *MAT_110). With P* = P / PHEL,
// T* = T / PHEL, sigma_HEL = 3/2 (HEL - PHEL) and r = 1 + C ln(max(epsdot / epsdot_0, 1)):
//   strength (eqs 1-3)  sigma* = sigma_i* - D (sigma_i* - sigma_f*),
//                       sigma_i* = A (P* + T*)^N r,  sigma_f* = min(SFMAX, B P*^M r)
//   damage (eqs 4, 5)   dD = d eps_p / (D1 (P* + T*)^D2),  D <= 1
//   pressure (eq 6)     P = K1 mu + K2 mu^2 + K3 mu^3 + dP (K1 mu + dP in tension),
//                       limited to P >= -T (1 - D)
//   bulking (eq 7)      dP_new = -K1 mu + sqrt((K1 mu + dP_old)^2 + 2 beta K1 dU),
//                       dU = U(D_old) - U(D_new), U = sigma_y^2 / (6 G) at the same pressure.
// The update is explicit in D, as the Holmquist-Johnson-Cook one: the pressure and strength of
// an increment use the damage and bulking pressure at its start; the damage it adds, and the
// bulking pressure the released energy builds, act from the next increment on.
#include "afemp/johnson_holmquist_ceramic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/materials/material.hpp"
#include "core/materials/model_parameters.hpp"

namespace afemp::core {

namespace {

// PointState::history slot of the bulking pressure dP.
constexpr std::size_t kBulkingPressure = 0;

}  // namespace

const char* JohnsonHolmquist2::history_name(std::size_t k) {
  return k == kBulkingPressure ? "bulking_pressure" : "";
}

double JohnsonHolmquist2::normalised_strength(double p_star, double damage,
                                              double strain_rate) const {
  const double rate = 1.0 + C * std::log(std::max(strain_rate / reference_strain_rate, 1.0));
  const double t_star = tensile_strength / hel_pressure;
  const double intact = A * std::pow(std::max(p_star + t_star, 0.0), N) * rate;
  double fractured = p_star > 0.0 ? B * std::pow(p_star, M) * rate : 0.0;
  if (max_fractured_strength > 0.0) fractured = std::min(fractured, max_fractured_strength);
  return intact - damage * (intact - fractured);
}

double JohnsonHolmquist2::fracture_strain(double p_star) const {
  const double t_star = tensile_strength / hel_pressure;
  return D1 * std::pow(std::max(p_star + t_star, 0.0), D2);
}

PointUpdate JohnsonHolmquist2::update_point(const Material& material, const Jh2Pressure& eos,
                                            PointState& point, const SymTensor& d_eps,
                                            double dt) const {
  const double p_old = pressure(point.stress);
  const SymTensor s_old = point.stress.deviator();
  const SymTensor de_dev = d_eps.deviator();
  const double d_vol = d_eps.trace();
  // As in constitutive_update: work per unit mass over the volume the increment acts on.
  const double inv_rho_work = 1.0 / (point.density * (1.0 + d_vol));

  // Pressure at the new density with the bulking pressure built so far, and the tension limit.
  const double mu = point.density / material.density - 1.0;
  double& bulking = point.history[kBulkingPressure];
  const double p_new =
      std::max(eos.pressure(mu, bulking), -tensile_strength * (1.0 - point.damage));

  // Deviator: elastic trial, radial return onto the strength at the new pressure.
  const double g = material.shear_modulus();
  SymTensor s_new = s_old + (2.0 * g) * de_dev;
  const double q_trial = von_mises(s_new);
  const double strain_rate =
      dt > 0.0 ? std::sqrt(2.0 / 3.0 * double_dot(de_dev, de_dev)) / dt : 0.0;
  const double p_star = p_new / hel_pressure;
  const double sigma_hel = hel_strength();
  const double yield = sigma_hel * normalised_strength(p_star, point.damage, strain_rate);
  double d_eps_p = 0.0;
  if (q_trial > yield) {
    // Perfectly plastic at fixed pressure: q_trial - 3 G d_eps_p = yield.
    d_eps_p = (q_trial - yield) / (3.0 * g);
    s_new *= yield > 0.0 ? yield / q_trial : 0.0;
  }
  point.plastic_strain += d_eps_p;

  // Damage; at the tension limit the fracture strain is 0 and any flow fractures the point.
  if (d_eps_p > 0.0) {
    const double damage_old = point.damage;
    const double eps_f = fracture_strain(p_star);
    point.damage = eps_f > 0.0 ? std::min(damage_old + d_eps_p / eps_f, 1.0) : 1.0;
    // Bulking: the elastic energy per unit volume the strength lost to the damage, at this
    // pressure, of which the fraction beta turns into pressure.
    const double u_old =
        std::pow(sigma_hel * normalised_strength(p_star, damage_old, strain_rate), 2) / (6.0 * g);
    const double u_new =
        std::pow(sigma_hel * normalised_strength(p_star, point.damage, strain_rate), 2) / (6.0 * g);
    bulking = eos.bulking_pressure(mu, bulking, std::max(u_old - u_new, 0.0), beta);
  }

  // Energy: trapezoidal deviatoric and volumetric work; p does not depend on e.
  point.energy +=
      (0.5 * double_dot(s_old + s_new, de_dev) - 0.5 * (p_old + p_new) * d_vol) * inv_rho_work;
  point.stress = s_new - p_new * SymTensor::identity();
  return {yield * d_eps_p * inv_rho_work};
}

void JohnsonHolmquist2::parameters(ParameterVisitor& v) {
  v.required("A", A, Range::positive());
  v.required("B", B, Range::non_negative());
  v.optional("C", C, 0.0, Range::non_negative());
  v.required("M", M, Range::positive());
  v.required("N", N, Range::positive());
  v.optional("reference_strain_rate", reference_strain_rate, 1.0, Range::positive());
  v.required("T", tensile_strength, Range::positive());
  v.optional("SFMAX", max_fractured_strength, 0.0, Range::non_negative());
  v.required("HEL", hel, Range::positive());
  // sigma_HEL = 3/2 (HEL - PHEL) > 0: the HEL's normal stress exceeds its pressure.
  v.required("PHEL", hel_pressure, {0.0, hel, true, true});
  v.optional("beta", beta, 1.0, Range::closed(0.0, 1.0));
  v.required("D1", D1, Range::positive());
  v.required("D2", D2, Range::non_negative());
}

double Jh2Pressure::pressure(double mu, double bulking) const {
  if (mu < 0.0) return K1 * mu + bulking;
  return mu * (K1 + mu * (K2 + mu * K3)) + bulking;
}

double Jh2Pressure::bulking_pressure(double mu, double bulking_old, double energy_loss,
                                     double beta) const {
  const double p = K1 * mu + bulking_old;
  return -K1 * mu + std::sqrt(p * p + 2.0 * beta * K1 * energy_loss);
}

double Jh2Pressure::tangent_bulk_modulus(double mu) const {
  if (mu < 0.0) return (1.0 + mu) * K1;
  return (1.0 + mu) * (K1 + mu * (2.0 * K2 + 3.0 * K3 * mu));
}

double Jh2Pressure::tangent_bulk_modulus(double mu, const PointState&) const {
  return tangent_bulk_modulus(mu);
}

void Jh2Pressure::parameters(ParameterVisitor& v) {
  v.required("K1", K1, Range::positive());
  v.optional("K2", K2, 0.0, Range::any());
  v.optional("K3", K3, 0.0, Range::non_negative());
  // The compression curve must rise for every mu >= 0: its slope K1 + 2 K2 x + 3 K3 x^2 is
  // smallest at x = max(0, -K2 / (3 K3)) (K3 > 0), and grows without bound only if K2 >= 0.
  const double x = K3 > 0.0 ? std::max(0.0, -K2 / (3.0 * K3)) : 0.0;
  v.require(K3 > 0.0 ? K1 + x * (2.0 * K2 + 3.0 * K3 * x) > 0.0 : K2 >= 0.0, "K2",
            out_of_range(K2,
                         "such that K1 + 2 K2 mu + 3 K3 mu^2 > 0 for mu >= 0 (pressure "
                         "rises with compression)"));
}

}  // namespace afemp::core
