// Small-strain tangent stiffness of the 8-node hexahedra:
//  - fully integrated with B-bar dilatation (Hughes, IJNME 15 (1980) 1413-1418; Hughes 2000,
//    sec. 4.5.2): K = sum_g w_g Bbar_g^T D_g Bbar_g over the 2x2x2 Gauss points of
//    fem/hexahedron_full.hpp, whose gradients it uses, so that it is the derivative of the nodal
//    forces add_stress_forces_bbar gives;
//  - one-point (Flanagan & Belytschko, IJNME 17 (1981) 679-706; fem/hexahedron_one_point.hpp):
//    K = V B^T D B with B of the mean gradients b_a / V, plus the stiffness of its hourglass
//    forms (fem/hourglass.hpp's stiffness form, fem/hourglass_assumed_strain.hpp's ASQBI form),
//    the derivative at small strain of the forces the explicit solver's routines give.
#pragma once

#include <array>

#include "afemp/material.hpp"
#include "afemp/scene.hpp"
#include "afemp/tensor.hpp"
#include "core/materials/small_strain_tangent.hpp"
#include "fem/hexahedron_full.hpp"
#include "fem/hexahedron_one_point.hpp"
#include "fem/sparse_assembly.hpp"

namespace afemp::fem {

// The B-bar small strain at point g of the nodal displacements u: the symmetric part of
// velocity_gradient_bbar applied to u.
core::SymTensor strain_bbar(const FullHex& e, int g, const HexVectors& u);

// k = sum_g w_g Bbar_g^T d[g] Bbar_g (d in Voigt order with engineering shear strains,
// core::VoigtMatrix), dof 3 a + i for component i of node a.
void hexahedron_stiffness_bbar(const FullHex& e, const std::array<core::VoigtMatrix, 8>& d,
                               HexMatrix& k);

// The one-point element's uniform small strain: the symmetric part of velocity_gradient applied
// to u (exact for every linear field; blind to the hourglass modes).
core::SymTensor strain_one_point(const OnePointHex& e, const HexVectors& u);

// k = V B^T d B, B of b_a / V: the derivative of add_stress_forces of the stress d : strain.
// Rank 6 at most: the twelve hourglass modes (four shapes, three directions) need the hourglass
// stiffness below.
void hexahedron_stiffness_one_point(const OnePointHex& e, const core::VoigtMatrix& d, HexMatrix& k);

// The hourglass stiffness of a one-point element at small strain, in generalised form: the
// hourglass displacements q_l,j = sum_a gamma_l,a u_a,j (fem/hourglass.hpp's gamma, orthogonal to
// every linear field), the generalised forces g_k,i = sum_lj h[3k+i][3l+j] q_l,j, the nodal
// forces f_a,i -= sum_k gamma_k,a g_k,i. It is the explicit rate forms summed from rest at fixed
// geometry (Q += K q dt, so that Q = K q): for the stiffness form h = k_h I, k_h =
// Q_hg (K + 4G/3) (sum_a b_a . b_a) / (3 V), rho c^2 of the elastic material at rest as the
// explicit form's modulus; for the assumed strain form h = R K_ASQBI R^T of the element's
// corotational frame R, with the shear modulus times the coefficient (its scale) as the explicit
// form takes it. Both stay elastic whatever the strength model, as the explicit forms do.
struct HourglassStiffness {
  std::array<std::array<double, 8>, 4> gamma{};
  std::array<double, 12 * 12> h{};  // row-major, index 3 k + i: mode k, direction i
};

// Throws std::invalid_argument for the viscous form, which resists only rates and so has no
// stiffness. x: the element's nodes, e = one_point_hex(x).
HourglassStiffness hourglass_stiffness(const HexVectors& x, const OnePointHex& e,
                                       const core::Material& material,
                                       const core::HourglassSettings& settings);

// The generalised forces g_k,i of the displacements u (global axes): the explicit stiffness
// form's state Q_k (fem/hourglass.hpp), and the assumed strain form's in global axes.
std::array<core::Vec3, 4> hourglass_generalised_forces(const HourglassStiffness& s,
                                                       const HexVectors& u);

// f -= the hourglass forces of the displacements u (as add_stress_forces, external minus
// internal).
void add_hourglass_forces(const HourglassStiffness& s, const HexVectors& u, HexVectors& f);

// k += the hourglass stiffness, the derivative of add_hourglass_forces' internal forces.
void add_hourglass_stiffness_matrix(const HourglassStiffness& s, HexMatrix& k);

// The stored hourglass energy q . h q / 2 of the displacements u.
double hourglass_energy(const HourglassStiffness& s, const HexVectors& u);

}  // namespace afemp::fem
