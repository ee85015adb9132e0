// Hourglass control of the one-point hexahedron after Flanagan & Belytschko, IJNME 17 (1981)
// 679-706: shape vectors gamma orthogonal to every linear field, and the viscous and stiffness
// resisting forces of LS-DYNA's *HOURGLASS types 3 and 5 (FB forms with exact volume).
#pragma once

#include <array>
#include <cmath>

#include "afemp/tensor.hpp"
#include "core/cube_root.hpp"
#include "fem/hexahedron.hpp"
#include "fem/hexahedron_lanes.hpp"
#include "fem/hexahedron_one_point.hpp"

namespace afemp::fem {

// The form is chosen per body in the scene (core::HourglassForm).
// Default coefficients Q_hg. Viscous: 0.1, LS-DYNA's default QM (above 0.15 the viscous forms
// can go unstable). Stiffness: 0.05, the top of the 0.03-0.05 LS-DYNA recommends for types 4/5
// on solids: on a cube of edge h, k_h below gives the hourglass mode the frequency
// sqrt(32 Q_hg) c / h, 0.37 of the bound 2 sqrt(3) c / h on the element's highest frequency,
// so the stiffness never limits the time step; a smaller value stiffens bending less but lets
// impact meshes hourglass visibly.
inline constexpr double kDefaultViscousHourglass = 0.1;
inline constexpr double kDefaultStiffnessHourglass = 0.05;

// Base vectors h_k of the four hourglass modes (fem/hexahedron_lanes.hpp).
using lanes::kHourglassBase;

struct HourglassModes {
  // gamma_k = h_k - (1/V) sum_b (h_k,b x_b) . b_a: the part of h_k that no linear field has.
  std::array<std::array<double, 8>, 4> gamma;
  double b_squared = 0.0;  // sum_a b_a . b_a, which scales the hourglass stiffness
};

HourglassModes hourglass_modes(const OnePointHex& e, const HexVectors& x);

// a_h of the viscous form and k_h of the stiffness form below (the hexahedron stage applies
// them to packs of elements with the kernels of fem/hexahedron_lanes.hpp).
inline double viscous_hourglass_factor(double coefficient, double density, double wave_speed,
                                       double volume) {
  const double v13 = core::cube_root(volume);
  return 0.25 * coefficient * density * wave_speed * v13 * v13;
}
inline double stiffness_hourglass_factor(double coefficient, double modulus, double b_squared,
                                         double volume) {
  return coefficient * modulus * b_squared / (3.0 * volume);
}

// Viscous form (LS-DYNA type 3): q_ik = sum_a v_a,i gamma_k,a and f_a,i -= a_h sum_k q_ik
// gamma_k,a with a_h = Q_hg rho c V^(2/3) / 4 (LS-DYNA Theory Manual, hourglass control: the
// a_h of its type 1 with FB's gamma in place of the base vectors; type 1 itself uses h_k and so
// fails the 3D patch test, Schwer et al., 5th European LS-DYNA Conference 2005). Returns the
// power the forces absorb, a_h sum q_ik^2 >= 0 (the hourglass energy rate).
double add_hourglass_viscous(const HourglassModes& m, const HexVectors& v, double coefficient,
                             double density, double wave_speed, double volume, HexVectors& f);

// Stiffness form (LS-DYNA type 5): the generalised hourglass forces Q_ik, persistent per element
// (caller-owned, zero at the start), follow Q_ik += k_h q_ik dt with
// k_h = Q_hg (lambda + 2 mu) (sum_a b_a . b_a) / (3 V), FB's scaling of the hourglass stiffness
// by the element's dilatational stiffness; then f_a,i -= sum_k Q_ik gamma_k,a. `modulus` is the
// constrained (P-wave) modulus lambda + 2 mu = rho c^2, and q is taken at the velocities of the
// step the stress is updated with. Q is kept in global axes and not rotated with the element,
// so an element that turns far while carrying hourglass deformation keeps its old force
// directions. Returns the power sum Q_ik q_ik, the
// rate of change of the stored hourglass energy.
double add_hourglass_stiffness(const HourglassModes& m, const HexVectors& v, double coefficient,
                               double modulus, double volume, double dt,
                               std::array<core::Vec3, 4>& hourglass_force, HexVectors& f);

}  // namespace afemp::fem
