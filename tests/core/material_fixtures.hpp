// Materials the material-law tests share (units mm, ms, g, N, MPa): a steel-like solid and
// OFHC copper with Johnson-Cook (Johnson & Cook 1983) and Mie-Grueneisen (Ma 2005 values).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/materials/material.hpp"

namespace afemp::core::fixtures {

// Scene text of the determinism tests: gravity and a Johnson-Cook copper with the
// Mie-Grueneisen EOS (Ma 2005's Taylor bar values, rate term off), to follow a [run] header
// line and precede the [[bodies]] table.
inline constexpr const char* kDeterminismCopperToml = R"(end_time = 1.0
gravity = [0, 0, -9.81e-3]
[materials.copper]
density = 8.93e-3
E = 117e3
nu = 0.35
strength = { model = "johnson-cook", A = 157, B = 425, n = 1.0 }
eos = { model = "mie-gruneisen", c0 = 3940, s = 1.49, gamma0 = 1.96 }
)";

// Scene text of the failure tests: 2024-T351 aluminium, material "al2024", with Johnson-Cook
// strength (A 265, B 426, n 0.34, C 0.015; no heating) and the Johnson & Cook (1985) damage
// constants of Johnson & Holmquist (1989): D1 = 0.13, D2 = 0.13, D3 = -1.5, D4 = 0.011
// (epsdot_0 = 1/s, 1e-3 per ms).
inline constexpr const char* kAl2024Toml = R"([materials.al2024]
density = 2.77e-3
E = 73100
nu = 0.33
strength = { model = "johnson-cook", A = 265, B = 426, n = 0.34, C = 0.015, reference_strain_rate = 1e-3 }
failure = { model = "johnson-cook", D1 = 0.13, D2 = 0.13, D3 = -1.5, D4 = 0.011, reference_strain_rate = 1e-3 }
)";

// The failure strain kAl2024Toml's Johnson & Cook (1985) law gives at a constant triaxiality
// sigma* and plastic strain rate (per ms): [D1 + D2 exp(D3 sigma*)] [1 + D4 ln(epsdot_p /
// epsdot_0)], the rate term taken as 1 below epsdot_0.
inline double al2024_failure_strain(double triaxiality, double rate_per_ms) {
  return (0.13 + 0.13 * std::exp(-1.5 * triaxiality)) *
         (1.0 + 0.011 * std::log(std::max(rate_per_ms / 1e-3, 1.0)));
}

inline Material steel(StrengthModel strength = Elastic{}) {
  Material m;
  m.name = "steel";
  m.density = 7.85e-3;
  m.youngs_modulus = 2.0e5;
  m.poisson_ratio = 0.3;
  m.strength = strength;
  return m;
}

inline JohnsonCook copper_jc() {
  JohnsonCook jc;
  jc.A = 90.0;
  jc.B = 292.0;
  jc.n = 0.31;
  jc.C = 0.025;
  jc.m = 1.09;
  jc.reference_strain_rate = 1e-3;  // 1/s in 1/ms
  jc.room_temperature = 293.0;
  jc.melt_temperature = 1356.0;
  return jc;
}

inline Material copper() {
  Material m;
  m.name = "copper";
  m.density = 8.93e-3;
  m.youngs_modulus = 1.24e5;
  m.poisson_ratio = 0.34;
  m.strength = copper_jc();
  m.eos = MieGruneisen{8.93e-3, 3940.0, 1.49, 1.96};
  m.thermal.specific_heat = 385.0;  // J/(kg K) = mm^2/(ms^2 K)
  m.thermal.taylor_quinney = 0.9;
  return m;
}

// A point of the material at rest in its reference state.
inline PointState at_rest(const Material& m) {
  PointState p;
  p.density = m.density;
  p.temperature = m.thermal.initial_temperature;
  return p;
}

}  // namespace afemp::core::fixtures
