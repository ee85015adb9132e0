// The Drucker-Prager soil model: a cone fitted to Mohr-Coulomb's friction angle and cohesion,
// non-associated flow through a dilatancy angle, and a tension cutoff on the mean stress
// (de Souza Neto, Peric & Owen 2008, "Computational Methods for Plasticity", ch. 6 and 8;
// the `dpm` model of MPM3D, Zhang, Chen & Liu 2016, "The Material Point Method", §5.2.6).
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

#include "afemp/model_parameters.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

struct Material;     // afemp/material.hpp
struct PointState;   // the internal point state of a constitutive update
struct PointUpdate;  // and what it reports
struct NoEos;        // afemp/equations_of_state.hpp

/// Drucker-Prager with a tension cutoff (drucker_prager.cpp). With the mean stress
/// sigma_m = tr(sigma) / 3 (tension positive: the pressure is -sigma_m) and tau = sqrt(J2):
///   shear yield        f_s = tau + q_phi sigma_m - k_phi <= 0
///   tension cutoff     f_t = sigma_m - sigma_t <= 0,   0 <= sigma_t <= k_phi / q_phi (the apex)
///   plastic potentials g_s = tau + q_psi sigma_m (associated when q_psi = q_phi), g_t = sigma_m,
/// perfectly plastic; the pressure law is the linear elastic one, K = E / (3 (1 - 2 nu)), so the
/// material takes no EOS. The scene gives the cone either as MPM3D's constants q_phi, k_phi,
/// q_psi or as Mohr-Coulomb's friction angle phi, cohesion c and dilatancy angle psi with a fit
/// (q_psi is the fit's q at psi).
struct DruckerPrager {
  static constexpr std::string_view name = "drucker-prager";  ///< in the scene file
  /// The cone through Mohr-Coulomb's outer (triaxial compression) edges, through its inner
  /// (triaxial extension) edges, or the plane-strain match (de Souza Neto et al. 2008,
  /// ch. 6; the last is also the cone inscribed in Mohr-Coulomb's hexagon).
  enum class Fit { outer, inner, plane_strain };
  static constexpr std::array<std::string_view, 3> fit_names{"outer", "inner", "plane-strain"};
  /// q of the fit at an angle (radians): q_phi at phi, q_psi at psi.
  static double cone_slope(Fit fit, double angle);
  /// k_phi of the fit at friction angle phi (radians) and cohesion c.
  static double cone_cohesion(Fit fit, double phi, double cohesion);

  double q_phi = 0.0;           ///< the cone's slope
  double k_phi = 0.0;           ///< its shear strength at zero mean stress
  double q_psi = 0.0;           ///< the plastic potential's slope, 0 <= q_psi <= q_phi
  double tension_cutoff = 0.0;  ///< sigma_t, the largest mean stress

  /// Its own pressure law is the linear elastic one: the material takes no EOS.
  using PressureLaw = NoEos;
  /// The update of one point: elastic trial, then the return onto the cone, the cutoff plane or
  /// the corner where they meet (the apex when sigma_t = k_phi / q_phi), the mean stress moving
  /// with the potential's volumetric part; the energy equation by the trapezoidal rule, the
  /// plastic work that of the stress on the whole plastic strain (volumetric part included).
  PointUpdate update_point(const Material& material, const NoEos& eos, PointState& point,
                           const SymTensor& d_eps, double dt) const;
  /// Its scene-file keys, ranges and rules (afemp/model_parameters.hpp).
  void parameters(ParameterVisitor& v);

  bool thermal() const { return false; }
  /// What the model reads of a point's history; solvers load only that (every model states it).
  static constexpr bool reads_plastic_strain = true;
  static constexpr bool reads_temperature = false;
  static constexpr bool reads_damage = false;
};

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::DruckerPrager;
}  // namespace afemp
