// Consistent tangents of the small-strain updates (core/materials/small_strain_tangent.hpp):
// elastic, K 1(x)1 + 2G I_dev, and for the radial returns of J2 (linear isotropic hardening)
// and Johnson-Cook (Simo & Hughes 1998, eq. 3.3.11, with their K' = H and
// ||xi|| = sqrt(2/3) q):
//   C = K 1(x)1 + 2G theta I_dev - 2G theta_bar n(x)n,
//   theta = 1 - 3G dp / q_trial,  theta_bar = 1 / (1 + H / (3G)) - (1 - theta),
// n the unit normal s_trial / |s_trial|, H = d sigma_y / d eps_p at the end of the increment
// (the isotropic-hardening case of Simo & Hughes box 3.2, whose return solves the consistency
// condition at eps_p + dp as JohnsonCook::update does). Johnson-Cook's rate and temperature are
// frozen: the update sees no time step (the rate factor is 1, the quasi-static curve) and the
// material's initial temperature, so sigma_y = (A + B eps_p^n)(1 - T*^m) with T* fixed and
// H = B n eps_p^(n-1) (1 - T*^m). A bar's 1-D return (small_strain_bar_update) takes the same
// H: its tangent is E H / (E + H).
#include "core/materials/small_strain_tangent.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "core/materials/model_parameters.hpp"

namespace afemp::core {
namespace {

// K 1(x)1 + 2G theta I_dev in Voigt form (engineering shear strains).
VoigtMatrix isotropic(double bulk, double shear) {
  VoigtMatrix c{};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) c[i][j] = bulk + 2.0 * shear * ((i == j) - 1.0 / 3.0);
    c[i + 3][i + 3] = shear;
  }
  return c;
}

// The components in Voigt order.
std::array<double, 6> voigt(const SymTensor& s) {
  return {s.xx, s.yy, s.zz, s.yz, s.xz, s.xy};
}

std::string strength_name(const StrengthModel& strength) {
  if (const auto* user = std::get_if<UserStrength>(&strength))
    return user->definition ? user->definition->name : "user";
  return std::string(model_name(strength));
}

// The strength model's own update of the deviator s (one of those check_small_strain_tangent
// allows).
DeviatoricResult deviatoric_update(const Material& material, SymTensor& s, const SymTensor& de_dev,
                                   const StrengthContext& context) {
  if (const auto* j2 = std::get_if<J2Plasticity>(&material.strength))
    return j2->update(s, de_dev, context);
  if (const auto* jc = std::get_if<JohnsonCook>(&material.strength))
    return jc->update(s, de_dev, context);
  return std::get<Elastic>(material.strength).update(s, de_dev, context);
}

// H = d sigma_y / d eps_p at plastic strain eps (> 0 after a plastic increment) and the frozen
// temperature.
double hardening_modulus(const Material& material, double eps, double temperature) {
  if (const auto* j2 = std::get_if<J2Plasticity>(&material.strength)) return j2->hardening;
  const JohnsonCook& jc = std::get<JohnsonCook>(material.strength);
  if (!(jc.B > 0.0)) return 0.0;
  const double power = std::pow(eps, jc.n);
  // (1 - T*^m) as the flow stress's ratio to its hardening factor A + B eps^n (> 0).
  return jc.B * jc.n * power / eps *
         (jc.flow_stress(eps, 0.0, temperature) / (jc.A + jc.B * power));
}

}  // namespace

void check_small_strain_tangent(const Material& material) {
  if (material.has_eos())
    throw std::invalid_argument("material '" + material.name + "': equation of state '" +
                                std::string(model_name(material.eos)) +
                                "' has no tangent for the static solve (only the bulk law "
                                "K tr(eps) without an EOS has one)");
  if (!std::holds_alternative<Elastic>(material.strength) &&
      !std::holds_alternative<J2Plasticity>(material.strength) &&
      !std::holds_alternative<JohnsonCook>(material.strength))
    throw std::invalid_argument("material '" + material.name + "': strength model '" +
                                strength_name(material.strength) +
                                "' has no consistent tangent for the static solve (elastic, j2 "
                                "and johnson-cook have one)");
}

SmallStrainResult small_strain_update(const Material& material, const SmallStrainPoint& from,
                                      const SymTensor& strain) {
  const double g = material.shear_modulus(), k = material.bulk_modulus();
  const SymTensor de_dev = (strain - from.strain).deviator();
  SymTensor s = from.deviator;
  const StrengthContext context{g, from.plastic_strain, material.thermal.initial_temperature, 0.0};
  SmallStrainResult out;
  out.plastic_strain = from.plastic_strain;
  out.tangent = isotropic(k, g);
  const double q_trial = von_mises(from.deviator + (2.0 * g) * de_dev);
  const DeviatoricResult r = deviatoric_update(material, s, de_dev, context);
  if (r.plastic_strain_increment > 0.0) {
    out.plastic_strain += r.plastic_strain_increment;
    const double hardening = hardening_modulus(material, out.plastic_strain, context.temperature);
    const double theta = 1.0 - 3.0 * g * r.plastic_strain_increment / q_trial;
    const double theta_bar = 1.0 / (1.0 + hardening / (3.0 * g)) - (1.0 - theta);
    out.tangent = isotropic(k, theta * g);
    // n = s / |s| (s is s_trial scaled), |s| = sqrt(2/3) q.
    const std::array<double, 6> n = voigt((1.0 / (std::sqrt(2.0 / 3.0) * von_mises(s))) * s);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) out.tangent[i][j] -= 2.0 * g * theta_bar * n[i] * n[j];
  }
  out.stress = s + (k * strain.trace()) * SymTensor::identity();
  return out;
}

SmallStrainBarResult small_strain_bar_update(const Material& material,
                                             const SmallStrainBarPoint& from, double strain) {
  const double e = material.youngs_modulus, d_strain = strain - from.strain;
  SymTensor s{(2.0 / 3.0) * from.stress, -from.stress / 3.0, -from.stress / 3.0, 0.0, 0.0, 0.0};
  const SymTensor de_dev{d_strain, -0.5 * d_strain, -0.5 * d_strain, 0.0, 0.0, 0.0};
  const StrengthContext context{e / 3.0, from.plastic_strain, material.thermal.initial_temperature,
                                0.0};
  const DeviatoricResult r = deviatoric_update(material, s, de_dev, context);
  SmallStrainBarResult out{s.xx - s.yy, from.plastic_strain, e};
  if (r.plastic_strain_increment > 0.0) {
    out.plastic_strain += r.plastic_strain_increment;
    const double hardening = hardening_modulus(material, out.plastic_strain, context.temperature);
    out.tangent = e * hardening / (e + hardening);
  }
  return out;
}

}  // namespace afemp::core
