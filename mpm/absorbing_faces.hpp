// Absorbing faces: the viscous boundary of Lysmer & Kuhlemeyer (1969) on the grid, for a body
// that continues beyond the face (a semi-infinite target): the face applies the tractions
// t_n = -rho c_L v_n and t_t = -rho c_S v_t, which a plane wave meeting the face at normal
// incidence takes without reflection. At a face node of tributary area A the damping is
// C = A rho c; with the material filling the node's half (or quarter) cell inside the grid,
// rho A = 2 m / h for face, edge and corner nodes alike, so C = 2 m c / h from the node's
// own mass. The grid momentum update applies it implicitly to a face node's updated velocity,
// v_new <- m v_new / (m + dt C), per component (c_L along the face normal, c_S across it),
// which is stable at any step; the work of the damping impulse leaves through the boundary
// and is booked as external work. The wave speeds are those of the one material the face
// meets (MpmSolver::setup_absorbing_faces, absorbing_faces.cpp).
//
// With a far field ([grid] far_field, core::FarField) the faces open onto an unbounded fluid at
// the ambient pressure p_inf, into which the flow leaves as a spherical one from the far
// field's centre. The ambient pressure itself acts through the whole grid: the internal force
// takes the stress relative to it, sigma + p_inf I (particle_to_grid.cpp), which changes no
// interior node's force (a uniform pressure has none) and makes the faces' static traction
// zero, while the EOS and the energy equation keep the absolute pressure; the ambient's work,
// -p_inf times the particles' volume change, is booked as external work (stress_update.cpp).
// Forces from the absolute stress would hold a particle lattice under a prestress of p_inf, whose
// negative geometric stiffness made the zero-energy modes of one particle per cell grow
// (measured: a still sphere of water at 10 MPa, kinetic energy x10 every 30 us). The price: a
// gas far below the ambient (a detonation bubble near its largest) is in tension in the
// internal force, and its particles clump until it holds the ambient again, so an explosion
// bubble does not slow down (docs/explosives.md, "The bubble period"); a gas near the ambient
// (the Minnaert test) is unaffected. The absolute stress with water of two particles per
// direction slowed that bubble in a trial, but threw a light gas near the ambient off.
// At a node on the face, at distance r from the centre and with
// cos(theta) = n . (x - centre) / r, the fluid beyond pushes back with the pressure q (relative
// to p_inf), which follows the first doubly asymptotic approximation (Geers 1978, J. Acoust.
// Soc. Am. 64, 1500; for a spherical surface it is exact), dq/dt = rho c dv_r/dt - (c / r) q,
// exact for an outgoing spherical wave of any frequency: at high frequency q = rho c v_r (the
// plane-wave damping), at low frequency q = rho r dv_r/dt (the added mass of the fluid outside
// r, which sets the period of a pulsating bubble). With v_r = u / cos(theta) (u the outward
// normal velocity) and q = Z (u - w), Z = rho c / cos(theta), the lag w follows
// dw/dt = (c / r)(u - w). The update is implicit in u and w (backward Euler), so stable at any
// step; q acts on the node's tributary area A of the face plane, and its work is booked as
// external work.
#pragma once

#include "afemp/tensor.hpp"

namespace afemp::mpm {

// The wave speeds of one absorbing face; off for the other conditions.
struct AbsorbingFace {
  bool on = false;
  double c_longitudinal = 0.0, c_shear = 0.0;  // sqrt((K + 4G/3) / rho0), sqrt(G / rho0)
  // A far field: the nodes on the face plane take far_field_update (normal component) instead
  // of the plane-wave damping; the halo beyond keeps the damping.
  bool far = false;
  double impedance = 0.0;  // rho0 c_L of the material that meets the face
  Vec3 centre{};
};

// One far-field face node (see above): its tributary area A on the face, Z = rho c / cos theta,
// k = c / r, and the outward sign s of the face normal (+1 on a max face).
struct FarFieldNode {
  double area = 0.0, impedance = 0.0, rate = 0.0, sign = 1.0;
};

// Updates the normal component v_new_a (after the grid forces) of a far-field face node of
// mass m with its start value v_a, and the node's lag w; returns the work of the far field's
// impulse over the step, J (u + u_new) / 2.
inline double far_field_update(const FarFieldNode& f, double m, double dt, double v_a,
                               double& v_new_a, double& lag) {
  const double u = f.sign * v_a;
  const double u_trial = f.sign * v_new_a;
  const double relax = 1.0 + dt * f.rate;
  const double beta = dt * f.area * f.impedance / (m * relax);
  const double u_new = (u_trial + beta * lag) / (1.0 + beta);
  lag = (lag + dt * f.rate * u_new) / relax;
  const double impulse = m * (u_new - f.sign * v_new_a);
  v_new_a = f.sign * u_new;
  return 0.5 * impulse * (u + u_new);
}

// Damps v_new of a face node of mass m (rate[a] = 2 c_a / h for component a, 0 where the node
// lies on no absorbing face) and returns the damping impulse's work over the step,
// J . (v + v_new) / 2 with the start and the damped velocity, as the body forces' work is
// counted in the grid momentum update.
inline double absorb(double m, const core::Vec3& rate, double dt, const core::Vec3& v,
                     core::Vec3& v_new) {
  const core::Vec3 before = v_new;
  for (int a = 0; a < 3; ++a) v_new[a] = before[a] / (1.0 + dt * rate[a]);
  return 0.5 * core::dot(m * (v_new - before), v + v_new);
}

}  // namespace afemp::mpm
