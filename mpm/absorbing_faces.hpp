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
#pragma once

#include "afemp/tensor.hpp"

namespace afemp::mpm {

// The wave speeds of one absorbing face; off for the other conditions.
struct AbsorbingFace {
  bool on = false;
  double c_longitudinal = 0.0, c_shear = 0.0;  // sqrt((K + 4G/3) / rho0), sqrt(G / rho0)
};

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
