// Holmquist-Johnson-Cook concrete: Holmquist, Johnson & Cook (1993), "A computational
// constitutive model for concrete subjected to large strains, high strain rates, and high
// pressures", 14th Int. Symp. Ballistics, pp. 591-600; LS-DYNA *MAT_111. With P* = P / fc,
// T* = T / fc, D the damage and r = 1 + C ln(max(epsdot / epsdot_0, 1)):
//   strength (paper eq 1)  sigma* = min(SFMAX, [A (1 - D) + B P*^N] r)          P* >= 0
//   in tension             sigma* = A (1 - D)(1 + P* / T*) r                     -T* <= P* < 0
//                          (the form of OpenRadioss /MAT/LAW126 and IMPETUS *MAT_HJC_CONCRETE:
//                          P*^N has no meaning below zero; it falls to 0 at the cutoff)
//   damage (paper eq 2)    dD = (d eps_p + d mu_p) / max(EFMIN, D1 (P* + T*)^D2),  D <= 1
//   pressure               HjcCompaction (hjc_compaction.cpp), limited to P >= -T (1 - D).
// epsdot is the equivalent deviatoric strain rate sqrt(2/3 de:de) / dt, d mu_p the growth of
// the permanent compaction. The update is explicit in D: pressure cutoff and strength use D at
// the start of the increment, the damage increment the pressure at its end.
#include "core/materials/holmquist_johnson_cook.hpp"

#include <algorithm>
#include <cmath>

#include "core/materials/model_parameters.hpp"

namespace afemp::core {

double HolmquistJohnsonCook::normalised_strength(double p_star, double damage,
                                                 double strain_rate) const {
  const double rate = std::max(strain_rate / reference_strain_rate, 1.0);
  const double rate_factor = 1.0 + C * std::log(rate);
  if (p_star >= 0.0)
    return std::min(max_strength, (A * (1.0 - damage) + B * std::pow(p_star, N)) * rate_factor);
  const double t_star = tensile_strength / compressive_strength;
  return std::max(A * (1.0 - damage) * (1.0 + p_star / t_star) * rate_factor, 0.0);
}

const char* HolmquistJohnsonCook::history_name(std::size_t k) {
  return k == kMaxCompaction ? "max_compaction" : "";
}

double HolmquistJohnsonCook::fracture_strain(double p_star) const {
  const double t_star = tensile_strength / compressive_strength;
  return std::max(min_fracture_strain, D1 * std::pow(std::max(p_star + t_star, 0.0), D2));
}

PointUpdate HolmquistJohnsonCook::update_point(const Material& material, const HjcCompaction& eos,
                                               PointState& point, const SymTensor& d_eps,
                                               double dt) const {
  const HolmquistJohnsonCook& strength = *this;
  const double p_old = pressure(point.stress);
  const SymTensor s_old = point.stress.deviator();
  const SymTensor de_dev = d_eps.deviator();
  const double d_vol = d_eps.trace();
  // As in constitutive_update: work per unit mass over the volume the increment acts on.
  const double inv_rho_work = 1.0 / (point.density * (1.0 + d_vol));

  // Pressure from the compaction law at the new density.
  const double mu = point.density / material.density - 1.0;
  double& mu_max = point.history[kMaxCompaction];
  const double mu_max_old = mu_max;
  mu_max = std::max(mu_max_old, mu);
  const double p_min = -strength.tensile_strength * (1.0 - point.damage);
  const double p_new = std::max(eos.pressure(mu, mu_max), p_min);
  // Permanent compaction never shrinks: the max only guards parameter sets whose unloading
  // lines cross.
  const double d_mu_p =
      std::max(eos.plastic_compaction(mu_max) - eos.plastic_compaction(mu_max_old), 0.0);

  // Deviator: elastic trial, radial return onto the yield surface at the new pressure.
  const double g = material.shear_modulus();
  SymTensor s_new = s_old + (2.0 * g) * de_dev;
  const double q_trial = von_mises(s_new);
  const double strain_rate =
      dt > 0.0 ? std::sqrt(2.0 / 3.0 * double_dot(de_dev, de_dev)) / dt : 0.0;
  const double fc = strength.compressive_strength;
  const double p_star = p_new / fc;
  const double yield = fc * strength.normalised_strength(p_star, point.damage, strain_rate);
  double d_eps_p = 0.0;
  if (q_trial > yield) {
    // Perfectly plastic at fixed pressure: q_trial - 3 G d_eps_p = yield.
    d_eps_p = (q_trial - yield) / (3.0 * g);
    s_new *= yield / q_trial;
  }
  point.plastic_strain += d_eps_p;
  point.damage =
      std::min(point.damage + (d_eps_p + d_mu_p) / strength.fracture_strain(p_star), 1.0);

  // Energy: trapezoidal deviatoric and volumetric work; p does not depend on e.
  point.energy +=
      (0.5 * double_dot(s_old + s_new, de_dev) - 0.5 * (p_old + p_new) * d_vol) * inv_rho_work;
  point.stress = s_new - p_new * SymTensor::identity();
  return {yield * d_eps_p * inv_rho_work};
}

void HolmquistJohnsonCook::parameters(ParameterVisitor& v) {
  v.required("A", A, Range::non_negative());
  v.required("B", B, Range::non_negative());
  v.required("N", N, Range::positive());
  v.optional("C", C, 0.0, Range::non_negative());
  v.required("fc", compressive_strength, Range::positive());
  v.required("T", tensile_strength, Range::positive());
  v.optional("reference_strain_rate", reference_strain_rate, 1.0, Range::positive());
  v.required("EFMIN", min_fracture_strain, Range::positive());
  v.required("SFMAX", max_strength, Range::positive());
  v.required("D1", D1, Range::non_negative());
  v.required("D2", D2, Range::non_negative());
}

}  // namespace afemp::core
