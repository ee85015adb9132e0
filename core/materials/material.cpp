// Material composition checks and the longitudinal wave speed sqrt((K_t + 4G/3) / rho) used
// for the explicit time step (Ma 2005, §2.2; K_t = rho dp/drho of the EOS at the point's state).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "core/materials/material.hpp"

namespace afemp::core {

namespace {

// Messages read "material 'NAME': PARAMETER = VALUE, must be RANGE". Conditions are written
// so that NaN fails them too.
void require(bool ok, const Material& m, const char* parameter, double value, const char* range) {
  if (ok) return;
  throw std::invalid_argument("material '" + m.name + "': " + parameter + " = " +
                              std::to_string(value) + ", must be " + range);
}

void validate_strength(const Material& m, const Elastic&) { (void)m; }

void validate_strength(const Material& m, const Fluid&) {
  if (!m.has_eos())
    throw std::invalid_argument("material '" + m.name + "': strength model fluid needs an eos "
                                "(a fluid has no shear and no bulk law of its own)");
}

void validate_strength(const Material& m, const J2Plasticity& j2) {
  require(j2.yield_stress >= 0.0, m, "yield_stress", j2.yield_stress, ">= 0");
  require(j2.hardening >= 0.0, m, "hardening", j2.hardening, ">= 0");
}

void validate_strength(const Material& m, const JohnsonCook& jc) {
  require(jc.A >= 0.0, m, "A", jc.A, ">= 0");
  require(jc.B >= 0.0, m, "B", jc.B, ">= 0");
  require(jc.n > 0.0, m, "n", jc.n, "> 0");
  require(jc.C >= 0.0, m, "C", jc.C, ">= 0");
  require(jc.m >= 0.0, m, "m", jc.m, ">= 0");
  require(jc.reference_strain_rate > 0.0, m, "reference_strain_rate", jc.reference_strain_rate,
          "> 0");
  if (jc.m > 0.0) {
    require(jc.melt_temperature > jc.room_temperature, m, "melt_temperature",
            jc.melt_temperature, "> room_temperature when m > 0");
  }
}

void validate_strength(const Material& m, const HolmquistJohnsonCook& hjc) {
  require(hjc.A >= 0.0, m, "A", hjc.A, ">= 0");
  require(hjc.B >= 0.0, m, "B", hjc.B, ">= 0");
  require(hjc.N > 0.0, m, "N", hjc.N, "> 0");
  require(hjc.C >= 0.0, m, "C", hjc.C, ">= 0");
  require(hjc.compressive_strength > 0.0, m, "fc", hjc.compressive_strength, "> 0");
  require(hjc.tensile_strength > 0.0, m, "T", hjc.tensile_strength, "> 0");
  require(hjc.reference_strain_rate > 0.0, m, "reference_strain_rate",
          hjc.reference_strain_rate, "> 0");
  require(hjc.min_fracture_strain > 0.0, m, "EFMIN", hjc.min_fracture_strain, "> 0");
  require(hjc.max_strength > 0.0, m, "SFMAX", hjc.max_strength, "> 0");
  require(hjc.D1 >= 0.0, m, "D1", hjc.D1, ">= 0");
  require(hjc.D2 >= 0.0, m, "D2", hjc.D2, ">= 0");
}

void validate_strength(const Material& m, const UserStrength& u) {
  if (!u.definition)
    throw std::invalid_argument("material '" + m.name +
                                "': user strength model without a definition (make it with "
                                "afemp::user_strength)");
  const std::vector<std::string>& names = u.definition->parameters;
  if (u.parameters.size() != names.size())
    throw std::invalid_argument("material '" + m.name + "': user strength model '" +
                                u.definition->name + "' takes " + std::to_string(names.size()) +
                                " parameters, got " + std::to_string(u.parameters.size()));
  for (std::size_t i = 0; i < names.size(); ++i)
    require(std::isfinite(u.parameters[i]), m, names[i].c_str(), u.parameters[i], "finite");
  if (u.definition->check) {
    try {
      u.definition->check(u.parameters);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("material '" + m.name + "': strength model '" +
                                  u.definition->name + "': " + e.what());
    }
  }
}

void validate_eos(const Material&, const NoEos&) {}

void validate_eos(const Material& m, const LinearEos& eos) {
  require(eos.bulk_modulus > 0.0, m, "bulk_modulus", eos.bulk_modulus, "> 0");
}

void validate_eos(const Material& m, const MieGruneisen& eos) {
  require(eos.rho0 > 0.0, m, "rho0", eos.rho0, "> 0");
  require(eos.c0 > 0.0, m, "c0", eos.c0, "> 0");
  require(eos.s >= 0.0, m, "s", eos.s, ">= 0");
  require(eos.gamma0 >= 0.0, m, "gamma0", eos.gamma0, ">= 0");
}

void validate_eos(const Material& m, const LinearPolynomialEos& eos) {
  require(eos.rho0 > 0.0, m, "rho0", eos.rho0, "> 0");
}

void validate_eos(const Material& m, const HjcCompaction& eos) {
  require(eos.crush_pressure() > 0.0, m, "PC", eos.crush_pressure(), "> 0");
  require(eos.crush_strain() > 0.0, m, "muc", eos.crush_strain(), "> 0");
  require(eos.lock_pressure() > eos.crush_pressure(), m, "PL", eos.lock_pressure(), "> PC");
  require(eos.lock_strain() > eos.crush_strain(), m, "mul", eos.lock_strain(), "> muc");
  const double k_e = eos.elastic_modulus();
  require(eos.k1() >= k_e, m, "K1", eos.k1(), ">= PC / muc (unloading stiffens as voids close)");
  // The dense curve must rise for every mubar >= 0: its slope K1 + 2 K2 x + 3 K3 x^2 is
  // smallest at x = max(0, -K2 / (3 K3)) (K3 > 0) or grows without bound only if K2 >= 0.
  require(eos.k3() >= 0.0, m, "K3", eos.k3(), ">= 0");
  if (eos.k3() > 0.0) {
    const double x = std::max(0.0, -eos.k2() / (3.0 * eos.k3()));
    const double slope = eos.k1() + x * (2.0 * eos.k2() + 3.0 * eos.k3() * x);
    require(slope > 0.0, m, "K2", eos.k2(),
            "such that K1 + 2 K2 x + 3 K3 x^2 > 0 for x >= 0 (pressure rises with compaction)");
  } else {
    require(eos.k2() >= 0.0, m, "K2", eos.k2(), ">= 0 when K3 = 0");
  }
  require(eos.plock_strain() > eos.crush_strain(), m, "mu_plock", eos.plock_strain(),
          "> muc (where the dense curve reaches PL; lower PL or mul)");
  const double crush_slope = eos.loading_slope(0.5 * (eos.crush_strain() + eos.plock_strain()));
  require(crush_slope <= k_e, m, "(PL - PC) / (mu_plock - muc)", crush_slope,
          "<= PC / muc (crushing is softer than the elastic response)");
}

void validate_eos(const Material& m, const Jwl& eos) {
  require(eos.rho0 > 0.0, m, "rho0", eos.rho0, "> 0");
  require(eos.A > 0.0, m, "eos A", eos.A, "> 0");
  require(eos.B > 0.0 && eos.B < eos.A, m, "eos B", eos.B, "in (0, A) (detonation products)");
  require(eos.R2 > 0.0, m, "eos R2", eos.R2, "> 0");
  require(eos.R1 > eos.R2, m, "eos R1", eos.R1, "> R2");
  require(eos.omega > 0.0, m, "eos omega", eos.omega, "> 0");
  require(eos.E0 >= 0.0, m, "eos E0", eos.E0, ">= 0");
  // The products at the reference volume with the detonation energy must push: a negative
  // pressure there is a set of parameters in another unit system, or mistyped.
  const double p1 = eos.pressure(1.0, eos.E0);
  require(p1 > 0.0, m, "eos pressure at V = 1 and E = E0", p1,
          "> 0 (check A, B, R1, R2, omega and E0 and their units)");
}

}  // namespace

bool Material::has_thermal_term() const {
  const bool softens = std::visit([](const auto& model) { return model.thermal(); }, strength);
  return softens && thermal.specific_heat > 0.0;
}

double Material::initial_energy() const {
  const auto* jwl = std::get_if<Jwl>(&eos);
  return jwl ? jwl->E0 / density : 0.0;
}

std::size_t Material::history_count() const {
  return std::visit(
      [](const auto& model) {
        if constexpr (is_user_strength<std::decay_t<decltype(model)>>)
          return model.history_count();
        else
          return model_history_size<std::decay_t<decltype(model)>>;
      },
      strength);
}

std::string Material::history_name(std::size_t k) const {
  return std::visit(
      [k](const auto& model) -> std::string {
        using Model = std::decay_t<decltype(model)>;
        if constexpr (is_user_strength<Model>)
          return model.definition && k < model.history_count()
                     ? model.definition->history_variables[k]
                     : std::string{};
        else if constexpr (model_history_size<Model> > 0)
          return k < model_history_size<Model> ? Model::history_name(k) : "";
        else
          return std::string{};
      },
      strength);
}

void Material::validate() const {
  require(density > 0.0, *this, "density", density, "> 0");
  // A fluid's E and nu may be left out (0): it has no shear and its EOS the pressure.
  const bool fluid = std::holds_alternative<Fluid>(strength);
  require(youngs_modulus > 0.0 || (fluid && youngs_modulus == 0.0), *this, "youngs_modulus",
          youngs_modulus, "> 0");
  require(poisson_ratio >= 0.0 && poisson_ratio < 0.5, *this, "poisson_ratio", poisson_ratio,
          "in [0, 0.5)");
  std::visit([this](const auto& model) { validate_strength(*this, model); }, strength);
  std::visit([this](const auto& model) { validate_eos(*this, model); }, eos);
  const bool hjc_strength = std::holds_alternative<HolmquistJohnsonCook>(strength);
  if (hjc_strength != std::holds_alternative<HjcCompaction>(eos)) {
    throw std::invalid_argument("material '" + name + "': strength model " +
                                (hjc_strength ? "holmquist-johnson-cook needs eos hjc-compaction"
                                              : "other than holmquist-johnson-cook cannot use "
                                                "eos hjc-compaction"));
  }
  if (const auto* compaction = std::get_if<HjcCompaction>(&eos)) {
    // The deviator uses G from E and nu, the compaction law K_e = PC / muc: they must agree.
    const double k_e = compaction->elastic_modulus();
    require(std::abs(bulk_modulus() - k_e) <= 1e-9 * k_e, *this, "bulk modulus E / (3 (1 - 2 nu))",
            bulk_modulus(), "= PC / muc (set E and nu from G and PC / muc)");
  }
  if (burn) {
    if (!std::holds_alternative<Jwl>(eos))
      throw std::invalid_argument("material '" + name + "': a burn (high explosive) needs eos jwl");
    require(burn->detonation_velocity > 0.0, *this, "burn D", burn->detonation_velocity, "> 0");
    require(burn->cj_pressure > 0.0, *this, "burn pcj", burn->cj_pressure, "> 0");
    const double v_cj = burn->cj_volume(density);
    require(v_cj > 0.0 && v_cj < 1.0, *this, "burn V_CJ = 1 - pcj / (density D^2)", v_cj,
            "in (0, 1) (check pcj, D and density and their units)");
  }
  if (const auto* jc = std::get_if<JohnsonCookFailure>(&failure)) {
    require(jc->reference_strain_rate > 0.0, *this, "failure reference_strain_rate",
            jc->reference_strain_rate, "> 0");
    // eps_f must stay positive at every triaxiality: D1 + D2 > 0 at sigma* = 0 and D1 >= 0
    // where exp(D3 sigma*) vanishes (D3 < 0), D2 >= 0.
    require(jc->D2 >= 0.0, *this, "failure D2", jc->D2, ">= 0");
    require(jc->D1 + jc->D2 > 0.0, *this, "failure D1 + D2", jc->D1 + jc->D2, "> 0");
    // eps_f falls as the triaxiality rises (D3 <= 0) and rises with the temperature (D5 >= 0),
    // as in every published set; a D5 < 0 would bring it to zero below the melt. D4 takes
    // either sign: steels that lose ductility with the rate have D4 < 0 (Weldox 460 E,
    // -0.0123: Borvik et al. 2001), whose rate factor would reach zero only at
    // epsdot* = exp(-1/D4), e^81 there; a point that got there would fail at once.
    require(jc->D3 <= 0.0, *this, "failure D3", jc->D3, "<= 0");
    require(jc->D5 >= 0.0, *this, "failure D5", jc->D5, ">= 0");
    require(jc->damage_threshold >= 0.0, *this, "failure damage_threshold", jc->damage_threshold,
            ">= 0");
    require(jc->critical_damage >= 0.0 && jc->critical_damage < 1.0, *this,
            "failure critical_damage", jc->critical_damage, "in [0, 1)");
  }
  if (const auto* p = std::get_if<PlasticStrainFailure>(&failure))
    require(p->strain > 0.0, *this, "failure strain", p->strain, "> 0");
  if (const auto* p = std::get_if<PrincipalStrainFailure>(&failure))
    require(p->strain > 0.0, *this, "failure strain", p->strain, "> 0");
  if (const auto* s = std::get_if<SpallFailure>(&failure)) {
    require(s->strength > 0.0, *this, "failure strength", s->strength, "> 0");
    require(s->impulse >= 0.0, *this, "failure impulse", s->impulse, ">= 0");
    require(s->exponent >= 1.0, *this, "failure exponent", s->exponent, ">= 1");
  }
  if (fails() && std::holds_alternative<HolmquistJohnsonCook>(strength))
    throw std::invalid_argument("material '" + name + "': holmquist-johnson-cook has its own "
                                "damage; it takes no failure model (remove failure / "
                                "failure_strain)");
  require(thermal.taylor_quinney >= 0.0 && thermal.taylor_quinney <= 1.0, *this,
          "taylor_quinney", thermal.taylor_quinney, "in [0, 1]");
  require(thermal.specific_heat >= 0.0, *this, "specific_heat", thermal.specific_heat, ">= 0");
}

double wave_speed(const Material& material, const PointState& point) {
  return std::visit([&](const auto& eos) { return wave_speed(material, eos, point); },
                    material.eos);
}

}  // namespace afemp::core
