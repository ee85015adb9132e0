// Two-node truss (rebar, truss bars): per-element kernels of the explicit FE step. The axial
// strain rate is taken along the current axis (corotational, so large rotations need no stress
// rotation), the stress comes from core::uniaxial_update, and N = sigma A acts along the axis.
#pragma once

#include "afemp/tensor.hpp"

namespace afemp::fem {

struct TrussKinematics {
  double length = 0.0;             // current length L = |xb - xa|
  core::Vec3 direction;            // unit axis e = (xb - xa) / L
  double axial_strain_rate = 0.0;  // d(ln L)/dt = (vb - va) . e / L
};

// Kinematics from the nodes' positions and velocities (positions at mid-step and velocities
// at the half step give a second-order strain increment rate * dt). Requires xa != xb.
TrussKinematics truss_kinematics(const core::Vec3& xa, const core::Vec3& xb, const core::Vec3& va,
                                 const core::Vec3& vb);

// Adds the nodal forces of the axial force N (tension positive): f_a += N e, f_b -= N e.
// They balance, and their power -(f_a . v_a + f_b . v_b) is N L rate.
void add_truss_forces(const TrussKinematics& k, double axial_force, core::Vec3& fa, core::Vec3& fb);

// Current cross-section from mass conservation, A = A0 L0 rho0 / (L rho), rho the density the
// material law tracks (core::uniaxial_update updates it with the lateral strain). The volume
// A L is then m / rho, which makes the bar's internal power N L rate equal to the power the
// material stores per unit mass times m: energy balances. Plastic flow keeps rho, so this is
// the volume-preserving A0 L0 / L there; elastically it contracts with Poisson's ratio, as
// OpenRadioss's truss (/PROP/TYPE2) does.
double current_area(double area0, double length0, double density0, double length, double density);

// Critical time step of a truss, L / c with the bar wave speed c = sqrt(E_t / rho); E_t is the
// uniaxial elastic modulus at the point's state (core::uniaxial_modulus, E without an EOS).
double truss_time_step(double length, double youngs_modulus_tangent, double density);

}  // namespace afemp::fem
