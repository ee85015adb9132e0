// A material as the scene file and the library describe it: a strength model for the
// deviator, an equation of state (or the hypoelastic bulk law) for the pressure, and thermal
// properties for adiabatic heating (Ma 2005, §2.2.1-2.2.2; the composition of
// OpenMPM3D / MPM3D-cpp). The point-wise updates are internal (core/materials/).
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <variant>

#include "afemp/drucker_prager.hpp"
#include "afemp/equations_of_state.hpp"
#include "afemp/failure_models.hpp"
#include "afemp/johnson_holmquist_ceramic.hpp"
#include "afemp/mooney_rivlin.hpp"
#include "afemp/neo_hookean.hpp"
#include "afemp/strength_models.hpp"
#include "afemp/user_material.hpp"

namespace afemp::core {

/// The deviatoric half of a material: one of the built-in strength models, or a user model
/// registered through afemp/user_material.hpp.
using StrengthModel =
    std::variant<Elastic, J2Plasticity, JohnsonCook, HolmquistJohnsonCook, UserStrength, Fluid,
                 JohnsonHolmquist2, DruckerPrager, NeoHookean, MooneyRivlin>;
/// The volumetric half of a material: no EOS (hypoelastic bulk law) or one of the built-in EOS.
using EquationOfState = std::variant<NoEos, LinearEos, MieGruneisen, LinearPolynomialEos,
                                     HjcCompaction, Jwl, Jh2Pressure>;

/// Programmed burn of a high explosive (LS-DYNA *MAT_HIGH_EXPLOSIVE_BURN; Wilkins' beta burn):
/// a point lights at t_l, its distance from the nearest detonation (Scene::detonations) over
/// the detonation velocity D plus that detonation's time; its burn fraction is
/// F = min(1, max(F1, F2)), never decreasing, with the lighting-time fraction
/// F1 = 2 (t - t_l) D / (3 l) after lighting (l the element's volume over its largest face,
/// for particles the grid cell: the front burns over 1.5 l) and the volumetric fraction
/// F2 = (1 - V) / (1 - V_CJ), V_CJ = 1 - p_CJ / (rho0 D^2); the pressure is F times the EOS's.
struct ProgrammedBurn {
  double detonation_velocity = 0.0;  ///< D
  double cj_pressure = 0.0;          ///< p_CJ
  bool lighting_time = true;         ///< F1 on
  bool volumetric = true;            ///< F2 on
  /// V_CJ = 1 - p_CJ / (rho0 D^2), the relative volume at the Chapman-Jouguet state.
  double cj_volume(double rho0) const {
    return 1.0 - cj_pressure / (rho0 * detonation_velocity * detonation_velocity);
  }
};

/// Adiabatic heating: the share of plastic work that becomes heat.
struct ThermalProperties {
  double specific_heat = 0.0;   ///< c_p per unit mass; 0 = no adiabatic heating
  double taylor_quinney = 0.9;  ///< fraction of plastic work turned into heat
  double initial_temperature = 293.0;
};

/// A material as the scene file's [materials.NAME] table: density, elastic constants, strength
/// model, EOS, thermal properties and failure strain (docs/scene-format.md).
struct Material {
  std::string name{};
  double density = 0.0;         ///< reference density rho0
  double youngs_modulus = 0.0;  ///< E
  double poisson_ratio = 0.0;   ///< nu
  StrengthModel strength = Elastic{};
  EquationOfState eos = NoEos{};
  ThermalProperties thermal{};
  double failure_strain = 0.0;  ///< equivalent plastic strain at failure; 0: none (erosion uses it)
  /// When a point fails (afemp/failure_models.hpp); a failure_strain without one acts as
  /// PlasticStrainFailure{failure_strain}.
  FailureModel failure = NoFailure{};
  /// The least pressure an EOS material carries (LS-DYNA's PC, <= 0): a fluid cavitates there,
  /// the pressure cut and the work done at it. -inf: no cutoff.
  double pressure_cutoff = -std::numeric_limits<double>::infinity();
  /// A high explosive: programmed burn of its JWL products (with eos Jwl only).
  std::optional<ProgrammedBurn> burn{};
  bool is_explosive() const { return burn.has_value(); }
  /// The specific internal energy its points start with where the body gives none: JWL
  /// products' detonation energy E0 / rho0 (E0 per unit reference volume), else 0.
  double initial_energy() const;
  /// Whether points of the material can fail.
  bool fails() const { return !std::holds_alternative<NoFailure>(failure); }
  /// The solvers integrate the strain tensor of its points (principal-strain failure).
  /// Whether the strength model reads the deformation gradient (hyperelastic models), which
  /// particles carry and hexahedra take from their nodes.
  bool reads_deformation_gradient() const {
    return std::visit(
        [](const auto& s) {
          return requires {
            std::decay_t<decltype(s)>::reads_deformation_gradient;
          };
        },
        strength);
  }
  /// Whether the strength model's energy splits as W_dev + K / 2 (J - 1)^2 with a deviatoric
  /// stress of its own, so that the mixed displacement-pressure MPM may supply the pressure
  /// (`[mpm] pressure = "mixed"`): the hyperelastic models that say so (the neo-Hookean solid's
  /// split form, Mooney-Rivlin).
  bool splits_volumetric_energy() const {
    return std::visit(
        [](const auto& s) {
          if constexpr (requires { s.splits_volumetric_energy(); })
            return s.splits_volumetric_energy();
          else
            return false;
        },
        strength);
  }
  bool needs_strain() const { return std::holds_alternative<PrincipalStrainFailure>(failure); }

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double bulk_modulus() const { return youngs_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  /// Sets E and nu from the shear modulus G and the bulk modulus K (for models given G).
  void set_shear_and_bulk_modulus(double g, double k) {
    youngs_modulus = 9.0 * k * g / (3.0 * k + g);
    poisson_ratio = (3.0 * k - 2.0 * g) / (2.0 * (3.0 * k + g));
  }
  bool has_eos() const { return !std::holds_alternative<NoEos>(eos); }
  /// History variables each point of the material carries: a user strength model's, or a
  /// built-in model's own (the largest compaction of Holmquist-Johnson-Cook concrete).
  std::size_t history_count() const;
  /// The name of history variable k (empty past history_count()).
  std::string history_name(std::size_t k) const;
  /// True when temperature must be integrated: a strength model that softens with
  /// temperature and a specific heat to turn plastic work into heat.
  bool has_thermal_term() const;
  /// Throws std::invalid_argument naming the parameter when a value is out of range.
  void validate() const;
};

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::EquationOfState;
using core::Material;
using core::ProgrammedBurn;
using core::StrengthModel;
using core::ThermalProperties;
}  // namespace afemp
