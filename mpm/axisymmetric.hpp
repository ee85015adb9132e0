// The axisymmetric MPM ([grid] axisymmetric = true): D. Sulsky & H. L. Schreyer, "Axisymmetric
// form of the material point method with applications to upsetting and Taylor impact problems",
// Comput. Methods Appl. Mech. Engrg. 139 (1996) 409-429. Fields turn about the z axis and depend
// on r and z only; x stands for r. Each particle stands for a ring: its volume is 2 pi r_p A_p
// (A_p its area in the r-z plane) and its mass rho times that. With those volumes the weak form
// of the momentum equation, integrated over the ring, is the 3-D sum of the particles' terms
// plus the hoop stress's:
//   f_I,r = - sum_p V_p (sigma_rr dN_I/dr + sigma_rz dN_I/dz + sigma_thth N_I / r_p),
//   f_I,z = - sum_p V_p (sigma_rz dN_I/dr + sigma_zz dN_I/dz),
// and the rate of deformation gains the hoop rate d_thth = v_r / r_p, v_r the particle's
// interpolated radial velocity.
//
// The grid is the 3-D one, one cell thick across the plane: nodes at y = -h/2 and +h/2 on
// symmetric faces, the particles on y = 0 between them. The two layers of nodes take equal
// halves of each particle's terms, so they carry the same velocities, their y components held
// at 0, and every 3-D stage (the grid update, the faces, the weld of bodies on one field, the
// stress update and the materials) runs unchanged: locally the y direction is the hoop one, so
// the hoop rate enters as d_yy and sigma_yy is the hoop stress. Near the axis v_r / r_p stays
// bounded: the linear hat interpolates v_r from 0 on the axis, so v_r / r_p is the nodal
// velocity over the cell. The axis has its limit all the same: a particle carried onto it
// keeps its mass while its ring's volume, 2 pi r A, shrinks with r, and its weight at the nodes
// off the axis, r / h, with it, so the grid barely feels its stress and its state can run away.
// A shaped charge's liner split along z everywhere left many pieces within 0.002 mm of the axis
// whose wave speeds reached 6e5 m/s and more, so a ring does not split within one cell of the axis
// (mpm/particle_splitting.cpp): so split, the liner ran to 0.2 mm cells with the step holding.
// Unsplit, it ran to 0.15 mm cells, but not to 0.1 mm, where the run went unstable at 19.3 us
// (examples/shaped_charge/README.md).
#pragma once

#include <cmath>
#include <numbers>

#include "afemp/tensor.hpp"

namespace afemp::mpm {

// The volume of the ring an r-z area `area` at radius r turns out.
inline double ring_volume(double r, double area) {
  return 2.0 * std::numbers::pi * r * area;
}

// The r-z edge of a square particle of ring volume `volume` at radius r (> 0).
inline double ring_particle_edge(double volume, double r) {
  return std::sqrt(volume / (2.0 * std::numbers::pi * r));
}

// A particle's edge: the cube root of its volume, or on an axisymmetric grid the square root of
// its ring's r-z area (x.x is its radius).
inline double particle_edge(double volume, const core::Vec3& x, bool axisymmetric) {
  return axisymmetric ? ring_particle_edge(volume, x.x) : std::cbrt(volume);
}

}  // namespace afemp::mpm
