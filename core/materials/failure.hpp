// Damage of the failure models (include/afemp/failure_models.hpp), composed with any strength
// model and EOS in finish_increment (constitutive_update.hpp): the damage after an increment
// from the state at its end. Johnson & Cook (1985) accumulates over the plastic strain
// increment; the plastic-strain model is D = eps_p / strain; spall fails at once when the
// tension (-p or the largest principal stress) passes the strength, or accumulates Tuler &
// Butcher's (1968) integral of its excess.
#pragma once

#include <algorithm>
#include <cmath>
#include <variant>

#include "afemp/failure_models.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

// d_eps_p: the increment's plastic strain over dt; p and s: pressure and deviator at its end.
inline double failure_damage(const FailureModel& model, double damage, double plastic_strain,
                             double d_eps_p, double dt, double p, const SymTensor& s,
                             double temperature) {
  if (const auto* jc = std::get_if<JohnsonCookFailure>(&model)) {
    if (!(d_eps_p > 0.0)) return damage;
    const double von_mises = std::sqrt(1.5 * double_dot(s, s));
    const double triaxiality = von_mises > 0.0 ? -p / von_mises : 0.0;
    const double rate = dt > 0.0 ? d_eps_p / dt / jc->reference_strain_rate : 1.0;
    double strain = (jc->D1 + jc->D2 * std::exp(jc->D3 * triaxiality)) *
                    (1.0 + jc->D4 * std::log(std::max(rate, 1.0)));
    if (jc->melt_temperature > jc->room_temperature) {
      const double t_star = std::clamp(
          (temperature - jc->room_temperature) / (jc->melt_temperature - jc->room_temperature), 0.0,
          1.0);
      strain *= 1.0 + jc->D5 * t_star;
    }
    // D1 < 0 (Armco iron) gives eps_f <= 0 at high triaxiality: failure at once.
    return std::min(damage + d_eps_p / std::max(strain, 1e-9), 1.0);
  }
  if (const auto* e = std::get_if<PlasticStrainFailure>(&model))
    return std::min(plastic_strain / e->strain, 1.0);
  if (const auto* sp = std::get_if<SpallFailure>(&model)) {
    const double tension = sp->criterion == SpallFailure::Criterion::pressure
                               ? -p
                               : largest_principal(s - p * SymTensor::identity());
    if (!(tension > sp->strength)) return damage;
    if (!(sp->impulse > 0.0)) return 1.0;
    return std::min(damage + std::pow(tension - sp->strength, sp->exponent) * dt / sp->impulse,
                    1.0);
  }
  // PrincipalStrainFailure: the solver holds the strain tensor (principal_strain_damage).
  return damage;
}

// The damage of the principal-strain model from the point's strain tensor (the sum of its
// increments), after the solver added this step's increment; other models: unchanged.
inline double principal_strain_damage(const FailureModel& model, double damage,
                                      const SymTensor& strain) {
  if (const auto* e = std::get_if<PrincipalStrainFailure>(&model))
    return std::max(damage, std::min(largest_principal(strain) / e->strain, 1.0));
  return damage;
}

}  // namespace afemp::core
