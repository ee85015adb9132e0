// examples/shaped_charge's charge as analysis/shaped_charge_per.hpp describes it, and its
// materials as analysis/liner_drive_1d.hpp takes them, for the tests of the PER estimate and of
// the liner's drive.
#pragma once

#include <cmath>

#include "analysis/liner_drive_1d.hpp"
#include "analysis/shaped_charge_per.hpp"

namespace afemp::analysis::test {

// The example's charge: PBX 9501 (rho 1.84e-3, D 8800, p_CJ 3.7e4, sqrt(2E) 2900) of radius 20
// in 2 mm of steel (7.85e-3), a 30-degree copper liner (8.93e-3), 2 mm thick, apex at 15.359,
// base at 50, lit on the axis at z = 0.
inline ConicalCharge example_charge() {
  ConicalCharge q;
  q.charge_radius = 20.0;
  q.case_thickness = 2.0;
  q.apex_z = 50.0 - 34.641;
  q.half_angle = std::atan(20.0 / 34.641);
  q.wall = 2.0;
  q.base_z = 50.0;
  q.detonation_z = 0.0;
  q.explosive_density = 1.84e-3;
  q.liner_density = 8.93e-3;
  q.case_density = 7.85e-3;
  q.detonation_velocity = 8800.0;
  q.cj_pressure = 3.7e4;
  q.gurney_velocity = 2900.0;
  return q;
}

// examples/shaped_charge's materials (mm, ms, g, MPa): PBX 9501's JWL (Dobratz & Crawford
// 1985), copper and steel by Steinberg's Mie-Grueneisen constants.
inline Ring1d pbx9501() {
  Ring1d x;
  x.kind = Ring1d::Kind::jwl;
  x.density = 1.84e-3;
  x.A = 8.524e5;
  x.B = 1.802e4;
  x.R1 = 4.6;
  x.R2 = 1.3;
  x.omega = 0.38;
  x.E0 = 1.02e4;
  x.detonation_velocity = 8800.0;
  return x;
}
inline Ring1d mie_gruneisen(double density, double c0, double s, double gamma0) {
  Ring1d m;
  m.density = density;
  m.c0 = c0;
  m.s = s;
  m.gamma0 = gamma0;
  return m;
}
inline Ring1d copper() {
  return mie_gruneisen(8.93e-3, 3940.0, 1.49, 2.0);
}
inline Ring1d steel() {
  return mie_gruneisen(7.85e-3, 4569.0, 1.49, 2.17);
}

}  // namespace afemp::analysis::test
