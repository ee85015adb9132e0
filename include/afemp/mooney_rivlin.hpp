// Hyperelastic strength: the compressible Mooney-Rivlin solid, whose stress is a function of the
// deformation gradient F (core/materials/mooney_rivlin.cpp).
#pragma once

#include <string_view>

#include "afemp/model_parameters.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

struct Material;     // afemp/material.hpp
struct PointState;   // the internal point state of a constitutive update
struct PointUpdate;  // and what it reports
struct NoEos;        // afemp/equations_of_state.hpp

/// Compressible two-parameter Mooney-Rivlin solid (Mooney 1940, Rivlin 1948) with the split
/// energy of the mixed u-p TLMPM paper's eq 14: W = C10 (I1bar - 3) + C01 (I2bar - 3)
/// + K / 2 (J - 1)^2, I1bar and I2bar the invariants of the isochoric Cbar = J^(-2/3) C. Its
/// Cauchy stress is sigma = (2 / J) dev[(C10 + I1bar C01) Bbar - C01 Bbar^2] + K (J - 1) I.
/// Its small-strain shear modulus is 2 (C10 + C01): the material's E and nu must give that
/// shear modulus (an error says which E does), and K comes from them. C01 = 0 is the
/// neo-Hookean solid. Like it, it reads F (particles and hexahedra), takes no EOS and is
/// refused on trusses.
struct MooneyRivlin {
  static constexpr std::string_view name = "mooney-rivlin";  ///< in the scene file
  double c10 = 0.0;                                          ///< C10 (stress), > 0
  double c01 = 0.0;                                          ///< C01 (stress), >= 0
  /// Its own pressure law, K (J - 1): the material takes no EOS.
  using PressureLaw = NoEos;
  /// The stress at the point's F and the energy equation by the trapezoidal rule on d_eps.
  PointUpdate update_point(const Material& material, const NoEos& eos, PointState& point,
                           const SymTensor& d_eps, double dt) const;
  /// C10 and C01, and the rule 2 (C10 + C01) = G of the material's E and nu.
  void parameters(ParameterVisitor& v);
  bool thermal() const { return false; }
  static constexpr bool reads_plastic_strain = false;
  static constexpr bool reads_temperature = false;
  static constexpr bool reads_damage = false;
  static constexpr bool reads_deformation_gradient = true;
  /// W = W_dev + K / 2 (J - 1)^2: the mixed u-p MPM may supply the pressure.
  bool splits_volumetric_energy() const { return true; }
};

}  // namespace afemp::core

namespace afemp {
using core::MooneyRivlin;
}  // namespace afemp
