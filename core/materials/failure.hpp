// Damage of the failure models (include/afemp/failure_models.hpp), composed with any strength
// model and EOS in finish_increment (constitutive_update.hpp): the damage after an increment
// from the state at its end. Johnson & Cook (1985) accumulates over the plastic strain
// increment; the plastic-strain model is D = eps_p / strain; spall fails at once when the
// tension (-p or the largest principal stress) passes the strength, or accumulates Tuler &
// Butcher's (1968) integral of its excess. Johnson-Cook damage may soften the deviator
// (damage_softening; Borvik et al. 2001).
#pragma once

#include <algorithm>
#include <cmath>
#include <variant>

#include "afemp/failure_models.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

// plastic_strain: the point's at the increment's end, d_eps_p: the increment's, over dt; p and
// s: pressure and deviator at its end (the stress's, softened where the damage softens it).
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
    // Borvik et al. (2001): damage grows over the part of the increment above the threshold.
    const double grows = std::min(d_eps_p, plastic_strain - jc->damage_threshold);
    if (!(grows > 0.0)) return damage;
    // D1 < 0 (Armco iron) gives eps_f <= 0 at high triaxiality: failure at once.
    return std::min(damage + grows / std::max(strain - jc->damage_threshold, 1e-9), 1.0);
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

// The factor on the stress deviator of a point with damage D: 1 - D_C D for Johnson-Cook
// damage coupled to the strength (Borvik et al. 2001: critical_damage D_C > 0), 1 otherwise.
inline double damage_softening(const FailureModel& model, double damage) {
  if (!(damage > 0.0)) return 1.0;
  const auto* jc = std::get_if<JohnsonCookFailure>(&model);
  return jc ? 1.0 - jc->critical_damage * std::min(damage, 1.0) : 1.0;
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
