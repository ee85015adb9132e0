// User strength models, as FE users know them from Abaqus/Explicit VUMAT and LS-DYNA user
// materials (*MAT_USER_DEFINED_MATERIAL_MODELS): the deviatoric half of a material, written
// and compiled in the user's own program, registered under a name that a scene file or a
// Material built in code uses. It runs in particles, hexahedra and trusses alike, on batches
// of points (structures of arrays): one call per batch, never one per point. The pressure
// still comes from the material's equation of state (or the hypoelastic bulk law), and the
// energy equation, adiabatic heating, bulk viscosity and time step stay the solvers' own.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "afemp/tensor.hpp"

namespace afemp::core {

/// One batch of material points handed to a user strength model: `count` points, every
/// per-point quantity an array of `count` doubles (a structure of arrays, VUMAT's layout).
/// Tensor components come in afemp order xx, yy, zz, yz, xz, xy, shear strains as tensor
/// (not engineering) components. The model reads the inputs and writes the outputs of every
/// point; it must not keep the pointers past the call.
struct StrengthBatch {
  std::size_t count = 0;               ///< points in this batch (at most a few hundred)
  double dt = 0.0;                     ///< time increment
  double shear_modulus = 0.0;          ///< G of the material, from E and nu
  const double* parameters = nullptr;  ///< the material's parameter values, in declared order
  /// Deviatoric strain increment dev(D) dt of each point, per component.
  const double* strain_increment[6] = {};
  const double* plastic_strain = nullptr;  ///< equivalent plastic strain at the start
  const double* temperature = nullptr;     ///< current temperature; null unless declared read
  /// Pressure p = -tr(sigma) / 3 at the start of the increment (positive in compression);
  /// null unless declared read.
  const double* pressure = nullptr;
  const double* density = nullptr;  ///< density at the end of the increment
  /// In: the stress deviator at the start, already rotated objectively (Jaumann);
  /// out: the deviator at the end of the increment.
  double* deviator[6] = {};
  /// History variables, variable-major: history[v * count + j] is variable v of point j.
  /// In: the values at the start; out: the values at the end. Null when none are declared.
  double* history = nullptr;
  /// Out: the equivalent plastic strain increment (0 for an elastic step). It feeds the plastic
  /// strain field, plastic work, adiabatic heating and the plastic-strain erosion and
  /// conversion criteria.
  double* plastic_strain_increment = nullptr;
  /// Out: the flow stress at the end of the increment; plastic work per unit volume is
  /// flow_stress * plastic_strain_increment.
  double* flow_stress = nullptr;

  /// Variable v of point j.
  double& history_at(std::size_t j, std::size_t v) const { return history[v * count + j]; }
  /// Point j's deviator (start value before the model writes it).
  SymTensor deviator_at(std::size_t j) const {
    return {deviator[0][j], deviator[1][j], deviator[2][j],
            deviator[3][j], deviator[4][j], deviator[5][j]};
  }
  /// Writes point j's deviator at the end of the increment.
  void set_deviator(std::size_t j, const SymTensor& s) const {
    deviator[0][j] = s.xx;
    deviator[1][j] = s.yy;
    deviator[2][j] = s.zz;
    deviator[3][j] = s.yz;
    deviator[4][j] = s.xz;
    deviator[5][j] = s.xy;
  }
  /// Point j's deviatoric strain increment.
  SymTensor strain_increment_at(std::size_t j) const {
    return {strain_increment[0][j], strain_increment[1][j], strain_increment[2][j],
            strain_increment[3][j], strain_increment[4][j], strain_increment[5][j]};
  }
};

/// A user strength model: its name, parameters and history variables, and the batch update.
struct UserStrengthDefinition {
  /// The name a scene file gives as strength.model; not one of the built-in models.
  std::string name{};
  /// Parameter names: the keys of the scene file's strength table, all required, handed to
  /// update() in this order (StrengthBatch::parameters).
  std::vector<std::string> parameters{};
  /// History variables every point of the material carries (written to the field output as
  /// the columns of "history").
  std::vector<std::string> history_variables{};
  /// Values of the history variables at the start of a run; empty: all 0.
  std::vector<double> initial_history{};
  bool reads_temperature = false;  ///< StrengthBatch::temperature is filled
  bool reads_pressure = false;     ///< StrengthBatch::pressure is filled
  /// The flow stress falls with temperature: with a specific heat in the material, plastic
  /// work heats the points (as for Johnson-Cook with m > 0). Needs reads_temperature.
  bool softens_with_temperature = false;
  /// Optional check of a material's parameter values; throw std::invalid_argument with a
  /// message naming the parameter and the allowed range to reject them.
  std::function<void(const std::vector<double>& parameters)> check{};
  /// The update: radial return (or any return) of every point of the batch.
  std::function<void(const StrengthBatch&)> update{};
};

/// Registers a user strength model for scene files and Materials built afterwards. Throws
/// InputError when the name is empty, a built-in model's, or already registered, when
/// update is empty, or when initial_history does not match history_variables.
void register_strength_model(UserStrengthDefinition definition);

/// The registered model of that name; throws InputError listing the registered names when
/// there is none.
std::shared_ptr<const UserStrengthDefinition> find_strength_model(const std::string& name);

/// The names of the registered user strength models, sorted.
std::vector<std::string> registered_strength_models();

/// A material's user strength model (a StrengthModel alternative): the registered definition
/// and this material's parameter values. Make it with user_strength().
struct UserStrength {
  std::shared_ptr<const UserStrengthDefinition> definition{};
  std::vector<double> parameters{};  ///< values in the definition's parameter order

  /// Whether plastic work must heat the points (with a specific heat).
  bool thermal() const { return definition && definition->softens_with_temperature; }
  /// Number of history variables each point carries.
  std::size_t history_count() const {
    return definition ? definition->history_variables.size() : 0;
  }
  /// What the solvers load for the model: plastic strain and temperature always (the batch
  /// hands both over), damage never; the model's own history is in its variables.
  static constexpr bool reads_plastic_strain = true;
  static constexpr bool reads_temperature = true;
  static constexpr bool reads_damage = false;
};

/// The strength model `name` (registered) with the parameter values given by name; throws
/// InputError naming a missing or unknown parameter and the model's parameter list.
UserStrength user_strength(const std::string& name,
                           const std::vector<std::pair<std::string, double>>& parameters);

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::find_strength_model;
using core::register_strength_model;
using core::registered_strength_models;
using core::StrengthBatch;
using core::user_strength;
using core::UserStrength;
using core::UserStrengthDefinition;
}  // namespace afemp
