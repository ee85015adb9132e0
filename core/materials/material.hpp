// A material is composed: a strength model for the deviator, an equation of state (or the
// hypoelastic bulk law) for the pressure, and thermal properties for adiabatic heating
// (Ma 2005, §2.2.1-2.2.2; the composition of OpenMPM3D / MPM3D-cpp). Solvers apply it to
// contiguous batches of points: std::visit once per batch, then a direct call per point.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "afemp/material.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

// A strength model with a pressure law of its own (Strength::PressureLaw, its update_point
// updates the whole point, as the Holmquist-Johnson-Cook concrete does), and such a law (which
// names its model, Eos::strength_model). Drucker-Prager's is NoEos, the linear elastic law,
// which the other models take too: its yield and its plastic flow couple pressure and deviator.
template <class Strength>
concept HasOwnPressureLaw = requires {
  typename Strength::PressureLaw;
};
template <class Eos>
concept IsOwnPressureLaw = requires {
  Eos::strength_model;
};

// Whether the material's EOS is a strength model's own pressure law.
inline bool has_own_pressure_law(const Material& material) {
  return std::visit([](const auto& eos) { return IsOwnPressureLaw<std::decay_t<decltype(eos)>>; },
                    material.eos);
}

// The strength and EOS pairs that form a material: a model with its own pressure law goes with
// that law, and no other model takes one (Material::validate checks it).
template <class Strength, class Eos>
inline constexpr bool composable = [] {
  if constexpr (HasOwnPressureLaw<Strength>)
    return std::is_same_v<Eos, typename Strength::PressureLaw>;
  else
    return !IsOwnPressureLaw<Eos>;
}();

// Whether the model runs on batches through a user's function (afemp/user_material.hpp)
// rather than per point.
template <class Strength>
inline constexpr bool is_user_strength = std::is_same_v<Strength, UserStrength>;

// Whether a strength model's update reads and writes PointState::damage; solvers leave it in
// memory for the others. Each model declares it.
template <class Strength>
inline constexpr bool has_damage_state = Strength::reads_damage;

// The history variables a built-in strength model keeps of its own (beyond the plastic strain,
// temperature, energy and damage every point has): a model that has some declares their count
// as `history_size` and names them with `history_name(k)` in its own file; the others have
// none. They live in the points' history store (the user models' store, carried through
// reordering, splitting, conversion, checkpoints and output) and reach the point-wise update in
// PointState::history.
template <class Strength>
inline constexpr std::size_t model_history_size = [] {
  if constexpr (requires { Strength::history_size; })
    return std::size_t{Strength::history_size};
  else
    return std::size_t{0};
}();

template <class Variant>
inline constexpr std::size_t largest_model_history = 0;
template <class... Strength>
inline constexpr std::size_t largest_model_history<std::variant<Strength...>> =
    std::max({std::size_t{1}, model_history_size<Strength>...});

// State of one material point through a constitutive update.
struct PointState {
  SymTensor stress;             // in: sigma^k already rotated objectively; out: sigma^{k+1}
  double plastic_strain = 0.0;  // equivalent plastic strain
  double temperature = 0.0;
  double energy = 0.0;   // specific internal energy (per unit mass)
  double density = 0.0;  // current density rho^{k+1}
  double damage = 0.0;   // scalar damage D in [0, 1]
  double burn = 1.0;     // a high explosive's burn fraction F (core/programmed_burn.hpp)
  // The deformation gradient at the end of the increment, for the models that read it
  // (reads_deformation_gradient: hyperelastic); null for the others.
  const Mat3* deformation_gradient = nullptr;
  // The mixed displacement-pressure MPM's projected pressure p (tension positive) for the
  // models whose energy splits off K / 2 (J - 1)^2 (splits_volumetric_energy): they take it in
  // place of K (J - 1); null when the scene's pressure is the point's own.
  const double* mixed_pressure = nullptr;
  // The strength model's own history variables (model_history_size of them are used).
  std::array<double, largest_model_history<StrengthModel>> history{};
};

// Moves a point's own history variables of model Strength between the points' history store
// (`stored`: the point's values, history_count of them) and its PointState.
template <class Strength>
inline void load_model_history(PointState& point, const double* stored) {
  for (std::size_t k = 0; k < model_history_size<Strength>; ++k) point.history[k] = stored[k];
}
template <class Strength>
inline void store_model_history(const PointState& point, double* stored) {
  for (std::size_t k = 0; k < model_history_size<Strength>; ++k) stored[k] = point.history[k];
}

struct PointUpdate {
  double plastic_work = 0.0;  // plastic work per unit mass done in this increment
};

// What the two halves of an update share: the start state split into deviator and pressure,
// the strain increment's deviator and trace, and 1 / (rho (1 + tr d eps)) for the work terms.
// constitutive_update is start_increment, the strength model's update of the deviator, then
// finish_increment; a user strength model (afemp/user_material.hpp) runs between the two on
// a batch of points.
// With damage coupled to the strength (failure.hpp, damage_softening) s_old is the effective
// (undamaged) deviator the strength model starts from, softening times it the stress's.
struct IncrementStart {
  double p_old = 0.0;
  SymTensor s_old;
  SymTensor de_dev;
  double d_vol = 0.0;
  double inv_rho_work = 0.0;
  double dt = 0.0;         // the increment's time step (the failure models' strain rate)
  double softening = 1.0;  // the deviator's factor 1 - D_C D at the start (failure.hpp)
};

// Fails as in finish_increment: only a material with a failure model may soften.
template <bool Fails = false>
inline IncrementStart start_increment(const Material& material, const PointState& point,
                                      const SymTensor& d_eps, double dt);

// A point of a material with a failure model that has failed (damage 1): it carries no shear
// and no tension from the next increment on.
inline bool has_failed(const PointState& point) {
  return point.damage >= 1.0;
}

// The volumetric half after the deviator s_new and the strength result r: plastic strain,
// energy equation, EOS pressure, stress and adiabatic heating (any strength model but HJC).
// Fails: the material has a failure model (core/materials/failure.hpp); a failed point takes
// no shear and no tension, and the others accumulate damage. A template parameter, so that
// materials without one compile to exactly the update they had (a runtime branch changed how
// the compiler fused the energy equation's multiply-adds, and so the last bits of every run).
template <class Eos, bool Fails = false>
PointUpdate finish_increment(const Material& material, const Eos& eos, bool thermal,
                             PointState& point, const IncrementStart& in, const SymTensor& s_new,
                             const DeviatoricResult& r);

// Updates stress, plastic strain, temperature and specific internal energy of one point for
// the strain increment d_eps = D dt (Ma 2005, eq 2-41):
//   deviator from the strength model; pressure from the EOS solved together with the energy
//   equation de = (s_mid : de_dev - p_mid tr(d_eps)) / rho (midpoint rule, closed form since
//   every EOS is linear in e), or p -= K tr(d_eps) without an EOS; temperature rises by
//   taylor_quinney * plastic work / c_p when has_thermal_term().
// Templated on the model types so that each batch runs one instantiation.
// A model with its own pressure law takes its update_point instead.
template <class Strength, class Eos, bool Fails = false>
PointUpdate constitutive_update(const Material& material, const Strength& strength, const Eos& eos,
                                bool thermal, PointState& point, const SymTensor& d_eps, double dt);

// Calls f(strength, eos) with the material's model types, instantiating only composable pairs:
// the one visit per batch of the solvers. Throws std::invalid_argument for a pair that
// Material::validate would reject.
template <class F>
decltype(auto) visit_models(const Material& material, F&& f) {
  using Result = decltype(f(std::declval<const Elastic&>(), std::declval<const NoEos&>()));
  return std::visit(
      [&](const auto& strength, const auto& eos) -> Result {
        if constexpr (composable<std::decay_t<decltype(strength)>, std::decay_t<decltype(eos)>>) {
          return f(strength, eos);
        } else {
          throw std::invalid_argument("material '" + material.name +
                                      "': a strength model with a pressure law of its own goes "
                                      "with that law only, and the law with it only");
        }
      },
      material.strength, material.eos);
}

// Bulk modulus rho dp/drho of the pressure response at the point's state: the EOS tangent, or
// K of the hypoelastic law without an EOS.
template <class Eos>
double tangent_bulk_modulus(const Material& material, const Eos& eos, const PointState& point);

// Longitudinal wave speed sqrt((K_t + 4G/3) / rho) at the point's state, K_t from
// tangent_bulk_modulus. The template is the per-batch form.
double wave_speed(const Material& material, const PointState& point);
template <class Eos>
double wave_speed(const Material& material, const Eos& eos, const PointState& point);

}  // namespace afemp::core

// constitutive_update is defined in core/materials/constitutive_update.hpp, included here.
#include "core/materials/constitutive_update.hpp"
