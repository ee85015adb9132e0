// Failure models: when a material point fails, composed with any strength model and EOS
// (core/materials/failure.hpp). A failed point keeps its mass and momentum, carries no shear
// and no tension (its pressure is cut at zero; compression still goes through the EOS), and
// shows damage 1 in the fields; elements of a body with erosion `material_failure` erode when
// they fail. Damage D in [0, 1] is the fraction of the way to failure.
#pragma once

#include <string_view>
#include <variant>

#include "afemp/model_parameters.hpp"

namespace afemp::core {

/// No failure (the default).
struct NoFailure {};

/// Johnson & Cook (1985, Eng. Fract. Mech. 21(1) 31-48) damage: over each plastic
/// strain increment D += d eps_p / eps_f with
/// eps_f = [D1 + D2 exp(D3 sigma*)] [1 + D4 ln(epsdot*)] [1 + D5 T*],
/// sigma* = -p / sigma_vm (the stress triaxiality), epsdot* = epsdot_p / epsdot_0 (taken as 1
/// below epsdot_0, as LS-DYNA *MAT_015 does), T* = (T - T_room) / (T_melt - T_room) in [0, 1];
/// the point fails at D = 1.
///
/// Optionally with the damage threshold and the coupling of Borvik, Hopperstad, Berstad &
/// Langseth (2001, Eur. J. Mech. A/Solids 20, 685-712; LS-DYNA *MAT_107's PD, DC and BETA = 1):
/// damage grows only while eps_p > damage_threshold, D += d eps_p / (eps_f - damage_threshold)
/// (the part of the increment above it), and the material softens as it grows: its stress
/// deviator is (1 - critical_damage D) times the undamaged one, which the strength model
/// evolves (the effective stress, Lemaitre's strain equivalence). Borvik's damage is
/// critical_damage D here, failing at D_C. Only the deviator softens: the pressure stays the
/// EOS's (a closed crack carries compression); the triaxiality is the stress's, -p over the
/// softened deviator's von Mises stress.
/// The strength model hardens with the plastic strain p itself: Borvik's damage-weighted r,
/// dr = (1 - D_C D) dp, is not kept apart, so the hardening runs a little ahead of his (r is
/// about (1 - D_C / 2) p at failure where the damage grows evenly).
struct JohnsonCookFailure {
  static constexpr std::string_view name = "johnson-cook";  ///< in the scene file
  double D1 = 0.0, D2 = 0.0, D3 = 0.0, D4 = 0.0, D5 = 0.0;
  double reference_strain_rate = 1.0;  ///< epsdot_0, in the scene's time unit
  double room_temperature = 293.0;
  double melt_temperature = 0.0;  ///< 0: no temperature term
  double damage_threshold = 0.0;  ///< p_d: plastic strain before damage grows, >= 0
  double critical_damage = 0.0;   ///< D_C in [0, 1): 0, no coupling (Johnson & Cook 1985)
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in failure_models.cpp.
  void parameters(ParameterVisitor& v);
};

/// Failure at an equivalent plastic strain (D = eps_p / strain).
struct PlasticStrainFailure {
  static constexpr std::string_view name = "plastic-strain";
  double strain = 0.0;  ///< > 0
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in failure_models.cpp.
  void parameters(ParameterVisitor& v);
};

/// Spall: the point fails when its tension passes the spall strength. The tension is -p
/// (hydrostatic tension, the pressure cutoff of LS-DYNA's spall models) or the largest
/// principal stress. Instantaneous (impulse = 0): it fails the step the tension exceeds the
/// strength. Cumulative (impulse > 0), Tuler & Butcher (1968, Int. J. Fract. Mech. 4(4)
/// 431-437): D += max(0, tension - strength)^exponent dt / impulse, failing at D = 1.
struct SpallFailure {
  static constexpr std::string_view name = "spall";
  enum class Criterion { pressure, principal_stress };
  Criterion criterion = Criterion::pressure;
  double strength = 0.0;  ///< spall strength (the threshold stress), > 0
  double impulse = 0.0;   ///< Tuler-Butcher K, stress^exponent x time; 0: instantaneous
  double exponent = 2.0;  ///< Tuler-Butcher lambda, >= 1
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in failure_models.cpp.
  void parameters(ParameterVisitor& v);
};

/// Failure at a principal strain (LS-DYNA *MAT_ADD_EROSION's MXEPS): the point fails when the
/// largest principal value of its strain tensor, the sum of D dt over its steps (the
/// logarithmic strain for coaxial stretching), reaches `strain`; D = eps_1 / strain, never
/// falling. The solvers integrate the strain tensor of such points.
struct PrincipalStrainFailure {
  static constexpr std::string_view name = "principal-strain";
  double strain = 0.0;  ///< > 0
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in failure_models.cpp.
  void parameters(ParameterVisitor& v);
};

/// A material's failure model.
using FailureModel = std::variant<NoFailure, JohnsonCookFailure, PlasticStrainFailure, SpallFailure,
                                  PrincipalStrainFailure>;

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::FailureModel;
using core::JohnsonCookFailure;
using core::NoFailure;
using core::PlasticStrainFailure;
using core::PrincipalStrainFailure;
using core::SpallFailure;
}  // namespace afemp
