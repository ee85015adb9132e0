// Physically stabilised one-point hexahedron: the ASQBI stabilisation of Belytschko & Bindeman,
// "Assumed strain stabilization of the eight node hexahedral element", CMAME 105 (1993) 225-260
// (LS-DYNA *HOURGLASS type 6 with QM = 1; code_aster's 3D_SI / HEXS8 element, reference manual
// r3.06.11 section 3, "Stabilisation de type Assumed Strain Method", its projection "ASQBI").
// Unlike FB's forms (fem/hourglass.hpp) the hourglass stiffness has no free coefficient: it is
// the strain energy of an assumed strain field under Hooke's law, so that
//  - a rectangular element bends exactly: the pure-bending displacement field of elasticity
//    (uniaxial stress E kappa z, or plane strain E/(1-nu^2) kappa z) gets its exact energy
//    E I kappa^2 L / 2 (with the matching modulus), whatever the aspect ratio (no shear locking);
//  - its stiffness stays bounded as nu -> 1/2 (no volumetric locking): the moduli involved are
//    2 mu (1 + nu_bar) = 2 mu / (1 - nu) = E / (1 - nu^2) and E = 2 mu (1 + nu), never lambda.
//
// Sources, by part (BB93's equations are cited by content, not number: the paper's text was not
// at hand, and the field below was read from code_aster's implementation of BB93, routine
// cast3d, ASQBI branch PROJ = 2, with nu_bar = nu / (1 - nu) as its nmas3d sets it):
//  [field]     the ASQBI assumed strain field of BB93 (code_aster r3.06.11 section 3);
//  [stiffness] its exact integral over a box, derived here (code_aster integrates the same field
//              with 2x2x2 Gauss points, which is exact for a box);
//  [general]   the box of a general element and [frame] the corotational frame: this file's
//              choices, both exact for a box (BB93 likewise evaluate the stabilisation in a
//              corotational system from the element's centre).
//
// [field] In the element's corotational frame (x, y, z along xi, eta, zeta, see below) take the
// element as the box of half-lengths a_j, c_j = 1/a_j, and write its hourglass velocity field
// as v_i = sum_k A_ik h_k(xi, eta, zeta), h_1..h_4 = eta zeta, zeta xi, xi eta, xi eta zeta
// (A_ik = q_ik / 8 for the q_ik = sum_a gamma_k,a v_a,i of fem/hourglass.hpp). Its strain rate
// beyond the uniform one of the one-point element is assumed to be, nu_bar = nu / (1 - nu):
//   eps_xx = c_x (A_x2 zeta + A_x3 eta + A_x4 eta zeta) - nu_bar (c_y A_y3 + c_z A_z2) xi
//            - nu (c_y A_y4 xi zeta + c_z A_z4 xi eta)
//   eps_yy = c_y (A_y1 zeta + A_y3 xi + A_y4 xi zeta) - nu_bar (c_x A_x3 + c_z A_z1) eta
//            - nu (c_x A_x4 eta zeta + c_z A_z4 xi eta)
//   eps_zz = c_z (A_z1 eta + A_z2 xi + A_z4 xi eta) - nu_bar (c_x A_x2 + c_y A_y1) zeta
//            - nu (c_x A_x4 eta zeta + c_y A_y4 xi zeta)
//   2 eps_xy = (c_y A_x1 + c_x A_y2) zeta,  2 eps_xz = (c_z A_x1 + c_x A_z3) eta,
//   2 eps_yz = (c_z A_y2 + c_y A_z3) xi.
// The normal strains are the trilinear field's; the shear strains keep only the twist
// (warping) terms, dropping the parasitic shear of the bending modes (shear locking) and all
// shear of the xi eta zeta mode; the Poisson terms (-nu_bar, -nu) make the stress across the
// depth of every bending mode zero and the xi eta zeta stress uniaxial, so that no mode is
// resisted by the bulk modulus (no volumetric locking).
//
// [stiffness] Closed form. With Hooke's law and, over the box, int xi^2 dV = V/3,
// int xi^2 eta^2 dV = V/9 and distinct monomials orthogonal, the energy W = 1/2 q . K q splits
// into independent blocks. With k = mu V / 96 (the 1/64 of A = q/8 times the V/3 and 1/2 of W):
//  - bending, one 2x2 block per plane, (i, j) the two in-plane directions' modes:
//      zeta plane (q_x2, q_y1), eta plane (q_x3, q_z1), xi plane (q_y3, q_z2):
//      Q_i = k c_i [(1 + nu_bar) c_i q_i + nu_bar c_j q_j] and the same with i, j swapped
//      (energy 2 mu [(1 + nu_bar)(s^2 + t^2) + 2 nu_bar s t] V / 6
//      = E / (1 - nu^2) [s^2 + 2 nu s t + t^2] V / 6, s, t = c A the two modes' curvatures times
//      the half-depth: plate bending, the stress across the transverse direction being zero);
//  - twist, one 3x3 block (q_x1, q_y2, q_z3), through the three assumed shears
//      G_z = c_y q_x1 + c_x q_y2, G_y = c_z q_x1 + c_x q_z3, G_x = c_z q_y2 + c_y q_z3:
//      Q_x1 = k/2 (c_y G_z + c_z G_y), Q_y2 = k/2 (c_x G_z + c_z G_x), Q_z3 = k/2 (c_x G_y + c_y
//      G_x) (energy mu G^2 V / 6 per shear, exactly the trilinear field's);
//  - the xi eta zeta mode, uniaxial: Q_i4 = k (1 + nu) c_i^2 q_i4 / 3 (energy E (c A)^2 V / 18).
// K is symmetric positive definite (rank 12) for -1 < nu < 1/2 and any mu > 0.
//
// [general] A non-rectangular element is taken through its Jacobian at the centre, g_j =
// dx/dxi_j at xi = 0 = (1/8) sum_a xi_a,j x_a. The half-lengths are a_j = 1 / |grad xi_j| with
// grad xi_j = (g_k x g_l) / (g_1 . g_2 x g_3) ((j, k, l) cyclic): half the distance between the
// faces xi_j = +-1 of the parallelepiped the centre Jacobian spans (the box's half-edges for a
// box), independent of the frame. The element is otherwise treated as that box: the
// off-diagonal terms of the inverse Jacobian in the corotational frame are neglected.
//
// [frame] The orthogonal polar factor R of N = [g_1/|g_1|, g_2/|g_2|, g_3/|g_3|],
// the rotation nearest (Frobenius) to the element's three unit centre-line directions, which
// treats the three alike (a Gram-Schmidt frame would favour the first); Newton's iteration
// X <- (X + X^-T) / 2 (Higham, SIAM J. Sci. Stat. Comput. 7 (1986) 1160-1174), quadratic for
// det N > 0. Its columns e_1, e_2, e_3 are the box's edge directions for a box, and turn exactly
// with a rigid rotation of the element, so the generalised stresses stored in it are not
// disturbed by rigid rotation and the forces turn with the element.
#pragma once

#include <array>

#include "afemp/tensor.hpp"
#include "fem/hexahedron.hpp"
#include "fem/hexahedron_one_point.hpp"
#include "fem/hourglass.hpp"

namespace afemp::fem {

// Generalised hourglass stresses (or hourglass velocities) of the 4 modes: [k] holds the
// components of mode k+1 in the corotational directions x, y, z. 12 doubles per element.
using HourglassComponents = std::array<core::Vec3, 4>;

struct AssumedStrainGeometry {
  std::array<core::Vec3, 3> axis;  // e_1, e_2, e_3 (global components), orthonormal, right-handed
  core::Vec3 inverse_half_length;  // c_j = |grad xi_j| at the centre
};

// The corotational frame and the c_j above. Needs det(g_1, g_2, g_3) > 0 (a well-formed
// element); otherwise (a tangled centre, which the caller should reject) it falls back to the
// Gram-Schmidt frame of g_1, g_2 and c_j = 1/|g_j|, so that nothing is NaN.
AssumedStrainGeometry assumed_strain_geometry(const HexVectors& x);

// K q for hourglass velocities (or displacements) q in the corotational frame, K the closed
// form above for the box of inverse half-lengths c and volume V.
HourglassComponents assumed_strain_stiffness_product(const core::Vec3& c, double volume,
                                                     double shear_modulus, double poisson_ratio,
                                                     const HourglassComponents& q);

// The step below from global hourglass velocities q_k = sum_a gamma_k,a v_a to the global
// generalised forces g_k (the nodal forces are then f_a -= sum_k gamma_k,a g_k): rotates q into
// the frame, adds K q^ dt to the stored stresses, rotates them back. Returns the midpoint
// power (Q^_old + Q^_new)/2 . q^ (see below).
double assumed_strain_hourglass_forces(const AssumedStrainGeometry& geo, double volume,
                                       double shear_modulus, double poisson_ratio, double dt,
                                       const std::array<core::Vec3, 4>& q,
                                       HourglassComponents& hourglass_stress,
                                       std::array<core::Vec3, 4>& g);

// One explicit step of the stabilisation, in rate form in the corotational frame:
//   q^_ik = e_i . sum_a gamma_k,a v_a   (hourglass velocities; zero for every linear field)
//   Q^   += K q^ dt                     (hourglass_stress: caller-owned, zero at the start)
//   f_a  -= sum_k gamma_k,a sum_i Q^_ik e_i
// x and e, m are the configuration the forces act on (as for add_hourglass_stiffness: the
// element's new coordinates, one_point_hex(x) and hourglass_modes(e, x)), v the step's
// velocities v^(n+1/2), shear_modulus and poisson_ratio the elastic constants (mu > 0,
// -1 < nu < 1/2). Returns the power sum_ik Q^_ik q^_ik with the updated Q^ (the rate of change
// of the stored stabilisation energy, = -sum_a f_a . v_a of the added forces). If
// midpoint_power is given it receives (Q^_old + Q^_new)/2 . q^, whose dt multiple is the exact
// change of the stored energy 1/2 q.K.q over the step for a constant K.
double add_hourglass_assumed_strain(const HexVectors& x, const HexVectors& v, const OnePointHex& e,
                                    const HourglassModes& m, double shear_modulus,
                                    double poisson_ratio, double dt,
                                    HourglassComponents& hourglass_stress, HexVectors& f,
                                    double* midpoint_power = nullptr);

}  // namespace afemp::fem
