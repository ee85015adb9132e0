// Drucker-Prager with a tension cutoff (afemp/drucker_prager.hpp). With the mean stress sigma_m
// (tension positive), tau = sqrt(J2), G and K the elastic moduli and the elastic trial state
// (sigma_m*, tau*):
//   shear return (de Souza Neto, Peric & Owen 2008, ch. 8, the smooth cone; MPM3D's M3DM9):
//     d lambda = f_s(sigma_m*, tau*) / (G + K q_phi q_psi),
//     sigma_m = sigma_m* - K q_psi d lambda,   tau = k_phi - q_phi sigma_m,
//   accepted where sigma_m <= sigma_t; otherwise, or with f_s <= 0 < f_t, the cutoff:
//     sigma_m = sigma_t,   tau = min(tau*, k_phi - q_phi sigma_t)
//   (tau* where the trial point lies inside the cone at sigma_t, the corner of cone and cutoff
//   otherwise: the apex when sigma_t is the apex). The two-surface return is consistent: the
//   corner is reached exactly when both multipliers, d lambda = (tau* - tau_c) / G on the cone
//   and (sigma_m* - sigma_t) / K - q_psi d lambda on the cutoff, are positive. MPM3D chooses
//   between the returns beyond sigma_t with FLAC's bisector h instead, which can leave tau
//   above the cone at sigma_t.
// The cone's fits to Mohr-Coulomb are those of de Souza Neto et al. (2008, ch. 6) in the
// mean stress (their eta and xi: q = eta, k = xi c).
#include "afemp/drucker_prager.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/materials/material.hpp"
#include "core/materials/model_parameters.hpp"

namespace afemp::core {

namespace {

struct ConeState {
  double mean = 0.0;  // sigma_m
  double tau = 0.0;   // sqrt(J2)
};

ConeState return_to_cone(const DruckerPrager& m, double mean, double tau, double g, double k) {
  const double f_shear = tau + m.q_phi * mean - m.k_phi;
  if (f_shear > 0.0) {
    const double d_lambda = f_shear / (g + k * m.q_phi * m.q_psi);
    const double mean_shear = mean - k * m.q_psi * d_lambda;
    if (mean_shear <= m.tension_cutoff) return {mean_shear, m.k_phi - m.q_phi * mean_shear};
  } else if (mean <= m.tension_cutoff) {
    return {mean, tau};
  }
  return {m.tension_cutoff, std::min(tau, m.k_phi - m.q_phi * m.tension_cutoff)};
}

}  // namespace

double DruckerPrager::cone_slope(Fit fit, double angle) {
  const double s = std::sin(angle), t = std::tan(angle);
  switch (fit) {
    case Fit::outer:
      return 6.0 * s / (std::numbers::sqrt3 * (3.0 - s));
    case Fit::inner:
      return 6.0 * s / (std::numbers::sqrt3 * (3.0 + s));
    case Fit::plane_strain:
      return 3.0 * t / std::sqrt(9.0 + 12.0 * t * t);
  }
  return 0.0;
}

double DruckerPrager::cone_cohesion(Fit fit, double phi, double cohesion) {
  const double s = std::sin(phi), c = std::cos(phi), t = std::tan(phi);
  switch (fit) {
    case Fit::outer:
      return 6.0 * cohesion * c / (std::numbers::sqrt3 * (3.0 - s));
    case Fit::inner:
      return 6.0 * cohesion * c / (std::numbers::sqrt3 * (3.0 + s));
    case Fit::plane_strain:
      return 3.0 * cohesion / std::sqrt(9.0 + 12.0 * t * t);
  }
  return 0.0;
}

PointUpdate DruckerPrager::update_point(const Material& material, const NoEos&, PointState& point,
                                        const SymTensor& d_eps, double) const {
  const double g = material.shear_modulus(), k = material.bulk_modulus();
  const double d_vol = d_eps.trace();
  // As in constitutive_update: work per unit mass over the volume the increment acts on.
  const double inv_rho_work = 1.0 / (point.density * (1.0 + d_vol));
  const SymTensor stress_old = point.stress;
  const SymTensor s_trial = stress_old.deviator() + (2.0 * g) * d_eps.deviator();
  const double mean_trial = stress_old.mean() + k * d_vol;
  const double tau_trial = std::sqrt(0.5 * double_dot(s_trial, s_trial));
  const ConeState r = return_to_cone(*this, mean_trial, tau_trial, g, k);
  const SymTensor s_new = tau_trial > 0.0 ? (r.tau / tau_trial) * s_trial : s_trial;
  point.stress = s_new + r.mean * SymTensor::identity();

  double plastic_work = 0.0;
  if (r.mean != mean_trial || r.tau != tau_trial) {
    // The plastic strain is what the elastic law does not account for: (s* - s) / 2G and
    // (sigma_m* - sigma_m) / K. Its equivalent is sqrt(2/3 d eps_p : d eps_p) (MPM3D's
    // d lambda sqrt(1/3 + 2/9 q_psi^2) on the cone). The stress's trapezoidal work on it is the
    // total trapezoidal work less the change of the elastic energy s:s/4G + sigma_m^2/2K, so the
    // elastic energy (internal - plastic) stays exactly that.
    const SymTensor de_plastic = (1.0 / (2.0 * g)) * (s_trial - s_new);
    const double dv_plastic = (mean_trial - r.mean) / k;
    point.plastic_strain +=
        std::sqrt(2.0 / 3.0 * (double_dot(de_plastic, de_plastic) + dv_plastic * dv_plastic / 3.0));
    const SymTensor d_eps_plastic = de_plastic + (dv_plastic / 3.0) * SymTensor::identity();
    plastic_work = 0.5 * double_dot(stress_old + point.stress, d_eps_plastic) * inv_rho_work;
  }
  point.energy += 0.5 * double_dot(stress_old + point.stress, d_eps) * inv_rho_work;
  return {plastic_work};
}

void DruckerPrager::parameters(ParameterVisitor& v) {
  // The Mohr-Coulomb form is read into the cone; a model built in code states the cone itself
  // (checking visits the angles at 0, within their ranges).
  const bool mohr_coulomb = v.reading() && v.has("friction_angle");
  double phi = 0.0, psi = 0.0, cohesion = 0.0;
  std::size_t fit = 0;
  v.optional("friction_angle", phi, 0.0, {0.0, 90.0, false, true});
  v.optional("dilatancy_angle", psi, 0.0, Range::closed(0.0, phi));
  v.optional("cohesion", cohesion, 0.0, Range::non_negative());
  v.choice("fit", fit, fit_names, mohr_coulomb ? std::nullopt : std::optional<std::size_t>(0));
  if (v.reading()) {
    for (const char* key : {"dilatancy_angle", "cohesion", "fit"})
      v.require(mohr_coulomb || !v.has(key), key,
                std::string(key) + " goes with friction_angle (the Mohr-Coulomb form of the cone)");
    for (const char* key : {"q_phi", "k_phi", "q_psi"})
      v.require(!mohr_coulomb || !v.has(key), key,
                "give the cone as friction_angle, cohesion, dilatancy_angle and fit, or as "
                "q_phi, k_phi and q_psi (MPM3D's constants), not both");
  }
  if (mohr_coulomb) {
    constexpr double degree = std::numbers::pi / 180.0;
    const Fit f = static_cast<Fit>(fit);
    q_phi = cone_slope(f, phi * degree);
    k_phi = cone_cohesion(f, phi * degree, cohesion);
    q_psi = cone_slope(f, psi * degree);
  } else {
    v.required("q_phi", q_phi, Range::non_negative());
    v.required("k_phi", k_phi, Range::non_negative());
    v.optional("q_psi", q_psi, 0.0, Range::closed(0.0, q_phi));
  }
  v.require(q_phi > 0.0 || k_phi > 0.0, mohr_coulomb ? "cohesion" : "k_phi",
            "a cone with neither friction nor cohesion has no strength (for that, strength "
            "model \"fluid\" with an eos)");
  // The cutoff lies at or below the apex; without friction there is no apex to default to.
  if (q_phi > 0.0) {
    const double apex = k_phi / q_phi;
    v.optional("tension_cutoff", tension_cutoff, apex, Range::closed(0.0, apex));
  } else {
    v.required("tension_cutoff", tension_cutoff, Range::non_negative());
  }
}

}  // namespace afemp::core
