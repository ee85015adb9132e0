// Hyperelastic strength: the compressible neo-Hookean solid, whose stress is a function of the
// deformation gradient F rather than of a strain increment (core/materials/neo_hookean.cpp).
#pragma once

#include <array>
#include <string_view>

#include "afemp/model_parameters.hpp"
#include "afemp/tensor.hpp"

namespace afemp::core {

struct Material;     // afemp/material.hpp
struct PointState;   // the internal point state of a constitutive update
struct PointUpdate;  // and what it reports
struct NoEos;        // afemp/equations_of_state.hpp

/// Compressible neo-Hookean solid in one of two forms (`form`), mu = G and K the material's
/// moduli from E and nu, J = det F, B = F F^T:
/// - `split` (the default): the split strain energy of the mixed u-p TLMPM paper (Zhang et al.
///   2022, eqs 14-16), W = mu / 2 (I1 I3^(-1/3) - 3) + K / 2 (J - 1)^2, I1 and I3 the invariants
///   of C = F^T F, Cauchy stress sigma = mu J^(-5/3) dev(B) + K (J - 1) I;
/// - `log`: W = mu / 2 (I1 - 3) - mu ln J + lambda / 2 (ln J)^2, lambda = K - 2 mu / 3 (Bonet &
///   Wood 2008), sigma = (mu (B - I) + lambda ln J I) / J: MPM3D-F90's `neoh`.
/// Both are exact for any rotation (no objective rate involved) and linear elastic with E and
/// nu for small strains; they part at finite strain. Its volumetric law is its own: the
/// material takes no EOS. It reads the deformation gradient, which the MPM tracks on particles
/// (both formulations) and hexahedra take from their nodes (fem/hexahedron_deformation_
/// gradient.hpp); trusses have none, and a scene that gives it to them is refused. Only the
/// split form takes the mixed u-p pressure.
struct NeoHookean {
  static constexpr std::string_view name = "neo-hookean";  ///< in the scene file
  enum class Form { split, log };
  static constexpr std::array<std::string_view, 2> form_names{"split", "log"};
  Form form = Form::split;  ///< the strain energy (above)
  /// Its own pressure law, K (J - 1): the material takes no EOS.
  using PressureLaw = NoEos;
  /// The stress at the point's F (point.deformation_gradient) and the energy equation by the
  /// trapezoidal rule on the increment d_eps (the work the stress does, so that the internal
  /// energy follows W to the time integration's order).
  PointUpdate update_point(const Material& material, const NoEos& eos, PointState& point,
                           const SymTensor& d_eps, double dt) const;
  /// `form` (default "split"); mu and K come from the material's E and nu.
  void parameters(ParameterVisitor& v);
  bool thermal() const { return false; }
  /// What the model reads of a point's history; solvers load only that (every model states it).
  static constexpr bool reads_plastic_strain = false;
  static constexpr bool reads_temperature = false;
  static constexpr bool reads_damage = false;
  static constexpr bool reads_deformation_gradient = true;
  /// Whether W = W_dev + K / 2 (J - 1)^2, so that the mixed u-p MPM may supply the pressure:
  /// the split form's; the log form's volumetric energy is lambda / 2 (ln J)^2 - mu ln J.
  bool splits_volumetric_energy() const { return form == Form::split; }
};

}  // namespace afemp::core

namespace afemp {
using core::NeoHookean;
}  // namespace afemp
