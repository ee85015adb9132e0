// Strength models: the deviatoric half of a material (Ma 2005, §2.2.1). Each model updates
// the stress deviator for one strain increment by radial return onto its yield surface.
// Bodies live in files named after each model; link-time optimisation inlines them into the
// material batch loops.
#pragma once

#include <cstddef>
#include <string_view>

#include "afemp/model_parameters.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

struct Material;      // afemp/material.hpp
struct PointState;    // the internal point state of a constitutive update
struct PointUpdate;   // and what it reports
class HjcCompaction;  // afemp/equations_of_state.hpp

/// What a deviatoric update reports back to the composition in material.hpp.
struct DeviatoricResult {
  double plastic_strain_increment = 0.0;  ///< equivalent plastic strain increment
  double flow_stress = 0.0;               ///< yield stress at the end of the increment
};

/// Inputs a strength model may need besides the deviator.
struct StrengthContext {
  double shear_modulus;   ///< G
  double plastic_strain;  ///< equivalent plastic strain at the start of the increment
  double temperature;     ///< current temperature
  double dt;              ///< time increment (for rate-dependent models)
};

/// Linear (hypo)elastic deviatoric response: s += 2 G de.
struct Elastic {
  static constexpr std::string_view name = "elastic";  ///< in the scene file
  DeviatoricResult update(SymTensor& s, const SymTensor& de_dev, const StrengthContext& c) const;
  bool thermal() const { return false; }
  /// What the model reads of a point's history; solvers load only that (every model states it).
  static constexpr bool reads_plastic_strain = false;
  static constexpr bool reads_temperature = false;
  static constexpr bool reads_damage = false;
};

/// No shear strength: a fluid, or detonation products (with an EOS). The deviator is zero.
struct Fluid {
  static constexpr std::string_view name = "fluid";
  DeviatoricResult update(SymTensor& s, const SymTensor& de_dev, const StrengthContext& c) const;
  bool thermal() const { return false; }
  static constexpr bool reads_plastic_strain = false;
  static constexpr bool reads_temperature = false;
  static constexpr bool reads_damage = false;
};

/// J2 plasticity with linear isotropic hardening (perfect plasticity when hardening = 0):
/// sigma_y = yield_stress + hardening * eps_p, radial return (Simo & Hughes box 3.2).
struct J2Plasticity {
  static constexpr std::string_view name = "j2";
  double yield_stress = 0.0;  ///< initial yield stress
  double hardening = 0.0;     ///< plastic modulus H = E Et / (E - Et)
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in j2_plasticity.cpp.
  void parameters(ParameterVisitor& v);
  DeviatoricResult update(SymTensor& s, const SymTensor& de_dev, const StrengthContext& c) const;
  bool thermal() const { return false; }
  /// What the model reads of a point's history; solvers load only that (every model states it).
  static constexpr bool reads_plastic_strain = true;
  static constexpr bool reads_temperature = false;
  static constexpr bool reads_damage = false;
};

/// Johnson-Cook flow stress (Ma 2005, eq 2-20):
/// sigma_y = (A + B eps_p^n)(1 + C ln(epsdot_p / epsdot_0))(1 - T*^m),
/// T* = (T - T_room) / (T_melt - T_room); the rate term is used only for epsdot_p > epsdot_0
/// (as LS-DYNA *MAT_015 does) and the thermal term only when m > 0 and T_melt > T_room.
struct JohnsonCook {
  static constexpr std::string_view name = "johnson-cook";
  double A = 0.0, B = 0.0, n = 1.0, C = 0.0, m = 0.0;
  double reference_strain_rate = 1.0;  ///< epsdot_0, in the scene's time unit
  double room_temperature = 293.0;
  double melt_temperature = 0.0;  ///< 0: no thermal softening
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in johnson_cook.cpp.
  void parameters(ParameterVisitor& v);
  double flow_stress(double eps_p, double eps_rate, double temperature) const;
  DeviatoricResult update(SymTensor& s, const SymTensor& de_dev, const StrengthContext& c) const;
  bool thermal() const { return m > 0.0 && melt_temperature > room_temperature; }
  /// What the model reads of a point's history; solvers load only that (every model states it).
  static constexpr bool reads_plastic_strain = true;
  static constexpr bool reads_temperature = true;
  static constexpr bool reads_damage = false;
};

/// Holmquist-Johnson-Cook concrete strength and damage (holmquist_johnson_cook.cpp), with
/// P* = P / fc, T* = T / fc and the strain-rate factor r = 1 + C ln(max(epsdot / epsdot_0, 1)):
///   sigma* = min(SFMAX, [A (1 - D) + B P*^N] r)   for P* >= 0
///   sigma* = A (1 - D)(1 + P* / T*) r             for -T* <= P* < 0
///   D += (d eps_p + d mu_p) / max(EFMIN, D1 (P* + T*)^D2).
/// Its yield stress depends on the pressure and its damage on the crushing of the pressure law,
/// so it is paired with its own pressure law HjcCompaction and updates a whole point
/// (update_point), not the deviator through update() like the models above.
struct HolmquistJohnsonCook {
  static constexpr std::string_view name = "holmquist-johnson-cook";
  double A = 0.0, B = 0.0, N = 1.0, C = 0.0;
  double compressive_strength = 0.0;   ///< fc, the quasi-static uniaxial compressive strength
  double tensile_strength = 0.0;       ///< T, the largest hydrostatic tension
  double reference_strain_rate = 1.0;  ///< epsdot_0, in the scene's time unit
  double min_fracture_strain = 0.0;    ///< EFMIN
  double max_strength = 0.0;           ///< SFMAX, normalised
  double D1 = 0.0, D2 = 0.0;
  /// Its own pressure law: a material with this strength model takes that EOS and no other.
  using PressureLaw = HjcCompaction;
  /// The update of one point (holmquist_johnson_cook.cpp): pressure from the compaction law
  /// with the tension cutoff -T (1 - D), deviator returned radially onto the yield surface at
  /// that pressure, damage from the plastic and crushing strain increments, and the energy
  /// equation of the other models (the pressure does not depend on e).
  PointUpdate update_point(const Material& material, const HjcCompaction& eos, PointState& point,
                           const SymTensor& d_eps, double dt) const;
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp), in
  /// holmquist_johnson_cook.cpp.
  void parameters(ParameterVisitor& v);
  /// sigma* at normalised pressure p_star, damage and equivalent strain rate.
  double normalised_strength(double p_star, double damage, double strain_rate) const;
  /// Plastic strain to fracture at normalised pressure p_star, max(EFMIN, D1 (P* + T*)^D2).
  double fracture_strain(double p_star) const;
  bool thermal() const { return false; }
  /// What the model reads of a point's history; solvers load only that (every model states it).
  static constexpr bool reads_plastic_strain = true;
  static constexpr bool reads_temperature = false;
  static constexpr bool reads_damage = true;
  /// Its own history variables (core/materials/material.hpp, model_history_size): one, named
  /// by history_name in holmquist_johnson_cook.cpp.
  static constexpr std::size_t history_size = 1;
  static const char* history_name(std::size_t k);
};

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::Elastic;
using core::Fluid;
using core::HolmquistJohnsonCook;
using core::J2Plasticity;
using core::JohnsonCook;
}  // namespace afemp
