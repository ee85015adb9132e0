// Material composition checks and the longitudinal wave speed sqrt((K_t + 4G/3) / rho) used
// for the explicit time step (Ma 2005, §2.2; K_t = rho dp/drho of the EOS at the point's state).
#include "core/materials/material.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "core/materials/model_parameters.hpp"

namespace afemp::core {

namespace {

// Messages read "material 'NAME': PARAMETER = VALUE, must be RANGE". Conditions are written
// so that NaN fails them too.
void require(bool ok, const Material& m, const char* parameter, double value, const char* range) {
  if (ok) return;
  throw std::invalid_argument("material '" + m.name + "': " + parameter + " = " +
                              std::to_string(value) + ", must be " + range);
}

// What a strength model needs of the rest of the material (beyond its own parameters).
template <class Model>
void validate_strength(const Material&, const Model&) {}

void validate_strength(const Material& m, const Fluid&) {
  if (!m.has_eos())
    throw std::invalid_argument("material '" + m.name +
                                "': strength model fluid needs an eos "
                                "(a fluid has no shear and no bulk law of its own)");
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
  // Each model's own ranges and rules (its parameters(), the scene parser's too).
  const MaterialConstants constants{density, youngs_modulus, bulk_modulus()};
  std::visit(
      [&](const auto& model) {
        check_parameters(model, name, "", constants);
        validate_strength(*this, model);
      },
      strength);
  std::visit([&](const auto& model) { check_parameters(model, name, "eos ", constants); }, eos);
  std::visit([&](const auto& model) { check_parameters(model, name, "failure ", constants); },
             failure);
  // A strength model with a pressure law of its own (Holmquist-Johnson-Cook concrete) takes
  // that law and no failure model (it has its own damage), and no other model takes the law.
  std::visit(
      [&](const auto& s, const auto& e) {
        using S = std::decay_t<decltype(s)>;
        using E = std::decay_t<decltype(e)>;
        if constexpr (HasOwnPressureLaw<S>) {
          if constexpr (!composable<S, E> && std::is_same_v<typename S::PressureLaw, NoEos>) {
            throw std::invalid_argument("material '" + name + "': strength model " +
                                        std::string(S::name) +
                                        " takes no eos: its pressure is linear elastic, K = E "
                                        "/ (3 (1 - 2 nu))");
          } else if constexpr (!composable<S, E>) {
            throw std::invalid_argument("material '" + name + "': strength model " +
                                        std::string(S::name) + " needs eos " +
                                        std::string(S::PressureLaw::name));
          } else {
            // The deviator uses G from E and nu, the law its bulk modulus: they must agree.
            if constexpr (IsOwnPressureLaw<E>) {
              const double k_e = e.elastic_modulus();
              if (!(std::abs(bulk_modulus() - k_e) <= 1e-9 * k_e))
                throw std::invalid_argument(
                    "material '" + name +
                    "': bulk modulus E / (3 (1 - 2 nu)) = " + format_value(bulk_modulus()) +
                    ", must be the bulk modulus of eos " + std::string(E::name) + ", " +
                    format_value(k_e) + " (set E and nu from G and it)");
            }
            if (fails())
              throw std::invalid_argument(
                  "material '" + name + "': " + std::string(S::name) +
                  (S::reads_damage ? " has its own damage; it" : " updates the whole point and") +
                  " takes no failure model (remove failure / failure_strain)");
          }
        } else if constexpr (IsOwnPressureLaw<E>) {
          throw std::invalid_argument("material '" + name + "': strength model other than " +
                                      std::string(E::strength_model) + " cannot use eos " +
                                      std::string(E::name));
        }
      },
      strength, eos);
  if (burn) {
    if (!std::holds_alternative<Jwl>(eos))
      throw std::invalid_argument("material '" + name + "': a burn (high explosive) needs eos jwl");
    require(burn->detonation_velocity > 0.0, *this, "burn D", burn->detonation_velocity, "> 0");
    require(burn->cj_pressure > 0.0, *this, "burn pcj", burn->cj_pressure, "> 0");
    const double v_cj = burn->cj_volume(density);
    require(v_cj > 0.0 && v_cj < 1.0, *this, "burn V_CJ = 1 - pcj / (density D^2)", v_cj,
            "in (0, 1) (check pcj, D and density and their units)");
  }
  require(thermal.taylor_quinney >= 0.0 && thermal.taylor_quinney <= 1.0, *this, "taylor_quinney",
          thermal.taylor_quinney, "in [0, 1]");
  require(thermal.specific_heat >= 0.0, *this, "specific_heat", thermal.specific_heat, ">= 0");
}

double wave_speed(const Material& material, const PointState& point) {
  return std::visit([&](const auto& eos) { return wave_speed(material, eos, point); },
                    material.eos);
}

}  // namespace afemp::core
