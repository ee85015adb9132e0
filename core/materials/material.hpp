// A material is composed: a strength model for the deviator, an equation of state (or the
// hypoelastic bulk law) for the pressure, and thermal properties for adiabatic heating
// (seed 001 §2.2.1-2.2.2; the composition of OpenMPM3D / MPM3D-cpp). Solvers apply it to
// contiguous batches of points: std::visit once per batch, then a direct call per point.
#pragma once

#include <string>
#include <variant>

#include "core/materials/equations_of_state.hpp"
#include "core/materials/strength_models.hpp"
#include "core/tensor.hpp"

namespace afemp::core {

using StrengthModel = std::variant<Elastic, J2Plasticity, JohnsonCook>;
using EquationOfState = std::variant<NoEos, LinearEos, MieGruneisen, LinearPolynomialEos>;

struct ThermalProperties {
  double specific_heat = 0.0;     // c_p per unit mass; 0 = no adiabatic heating
  double taylor_quinney = 0.9;    // fraction of plastic work turned into heat
  double initial_temperature = 293.0;
};

struct Material {
  std::string name;
  double density = 0.0;        // reference density rho0
  double youngs_modulus = 0.0;  // E
  double poisson_ratio = 0.0;   // nu
  StrengthModel strength = Elastic{};
  EquationOfState eos = NoEos{};
  ThermalProperties thermal;
  double failure_strain = 0.0;  // equivalent plastic strain at failure; 0: none (erosion uses it)

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  bool has_eos() const { return !std::holds_alternative<NoEos>(eos); }
  // True when temperature must be integrated: a strength model that softens with
  // temperature and a specific heat to turn plastic work into heat.
  bool has_thermal_term() const;
  // Throws std::invalid_argument naming the parameter when a value is out of range.
  void validate() const;
};

// State of one material point through a constitutive update.
struct PointState {
  SymTensor stress;             // in: sigma^k already rotated objectively; out: sigma^{k+1}
  double plastic_strain = 0.0;  // equivalent plastic strain
  double temperature = 0.0;
  double energy = 0.0;          // specific internal energy (per unit mass)
  double density = 0.0;         // current density rho^{k+1}
};

struct PointUpdate {
  double plastic_work = 0.0;  // plastic work per unit mass done in this increment
};

// Updates stress, plastic strain, temperature and specific internal energy of one point for
// the strain increment d_eps = D dt (seed 001 eq 2-41):
//   deviator from the strength model; pressure from the EOS solved together with the energy
//   equation de = (s_mid : de_dev - p_mid tr(d_eps)) / rho (midpoint rule, closed form since
//   every EOS is linear in e), or p -= K tr(d_eps) without an EOS; temperature rises by
//   taylor_quinney * plastic work / c_p when has_thermal_term().
// Templated on the model types so that each batch runs one instantiation.
template <class Strength, class Eos>
PointUpdate constitutive_update(const Material& material, const Strength& strength, const Eos& eos,
                                bool thermal, PointState& point, const SymTensor& d_eps, double dt);

// Longitudinal wave speed sqrt((K_t + 4G/3) / rho) at the point's state, K_t the EOS tangent
// bulk modulus (or K without an EOS). The template is the per-batch form.
double wave_speed(const Material& material, const PointState& point);
template <class Eos>
double wave_speed(const Material& material, const Eos& eos, const PointState& point);

}  // namespace afemp::core

// constitutive_update is defined in core/materials/constitutive_update.hpp, included here.
#include "core/materials/constitutive_update.hpp"
