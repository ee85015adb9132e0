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
// field's centre. The ambient pressure enters in one of two forms (far_field.stress):
// - gauge (the default): the internal force takes the stress relative to the ambient,
//   sigma + p_inf I (particle_to_grid.cpp), which changes no interior node's force (a uniform
//   pressure has none) and makes the faces' static traction zero, while the EOS and the energy
//   equation keep the absolute pressure; the ambient's work, -p_inf times the particles'
//   volume change, is booked as external work (stress_update.cpp). A prestressed lattice of one
//   particle per cell is then stable, and a gas near the ambient (the Minnaert test) is right.
//   But an empty cell reads as the ambient: a gas far below it (an explosion bubble near its
//   largest) is in tension in the internal force, its particles clump until it holds the
//   ambient again, and the bubble does not slow down (docs/explosives.md, "The bubble period").
// - absolute: the internal force takes the stress itself, and the ambient acts on the face
//   plane's nodes as a static traction p_inf A (A the node's tributary area, which balances a
//   uniform -p_inf I exactly with linear shape functions and a full lattice). An empty cell
//   reads as vacuum: a cavity of air at 1 % of the ambient closes in Rayleigh's time (within
//   2.3 %), and an explosion bubble slows and recollapses (first period 11 % over
//   Rayleigh-Willis at 2 mm cells, 5 % at 1 mm; examples/underwater_explosion/bubble.toml).
//   The prestress destabilises zero-energy modes instead: water needs two particles per cell
//   direction (at one, the kinetic energy of still water at 10 MPa grew x10 every 30 us), and
//   a gas whose bulk modulus is near its pressure (gamma p) at the ambient is thrown off (the
//   Minnaert gas jumped 3-30 MPa): use the gauge form there.
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
// k = c / r, the outward sign s of the face normal (+1 on a max face), and the static pressure
// p_s pushing on it from beyond (the ambient under the absolute stress; 0 under the gauge).
struct FarFieldNode {
  double area = 0.0, impedance = 0.0, rate = 0.0, sign = 1.0, static_pressure = 0.0;
};

// Updates the normal component v_new_a (after the grid forces) of a far-field face node of
// mass m with its start value v_a, and the node's lag w; returns the work of the far field's
// impulse (the static traction's with it) over the step, J (u + u_new) / 2.
inline double far_field_update(const FarFieldNode& f, double m, double dt, double v_a,
                               double& v_new_a, double& lag) {
  const double u = f.sign * v_a;
  const double u_trial = f.sign * v_new_a - dt * f.static_pressure * f.area / m;
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
