// examples/shaped_charge's charge as analysis/shaped_charge_per.hpp describes it, for the
// tests of the PER estimate and of the liner's drive (tests/analysis).
#pragma once

#include <cmath>

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

}  // namespace afemp::analysis::test
