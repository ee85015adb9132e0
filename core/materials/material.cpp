// Material composition checks and the longitudinal wave speed sqrt((K_t + 4G/3) / rho) used
// for the explicit time step (seed 001 §2.2; K_t = rho dp/drho of the EOS at the point's state).
#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>

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

}  // namespace

bool Material::has_thermal_term() const {
  const bool softens = std::visit([](const auto& model) { return model.thermal(); }, strength);
  return softens && thermal.specific_heat > 0.0;
}

void Material::validate() const {
  require(density > 0.0, *this, "density", density, "> 0");
  require(youngs_modulus > 0.0, *this, "youngs_modulus", youngs_modulus, "> 0");
  require(poisson_ratio >= 0.0 && poisson_ratio < 0.5, *this, "poisson_ratio", poisson_ratio,
          "in [0, 0.5)");
  std::visit([this](const auto& model) { validate_strength(*this, model); }, strength);
  std::visit([this](const auto& model) { validate_eos(*this, model); }, eos);
  require(thermal.taylor_quinney >= 0.0 && thermal.taylor_quinney <= 1.0, *this,
          "taylor_quinney", thermal.taylor_quinney, "in [0, 1]");
  require(thermal.specific_heat >= 0.0, *this, "specific_heat", thermal.specific_heat, ">= 0");
}

double wave_speed(const Material& material, const PointState& point) {
  return std::visit([&](const auto& eos) { return wave_speed(material, eos, point); },
                    material.eos);
}

}  // namespace afemp::core
