#pragma once

// Scene text the explosive and fluid tests share (tests/mpm/test_detonation.cpp,
// tests/validation/test_gurney.cpp, the water tests): TNT (LS-DYNA's example set, which passes
// through its own Chapman-Jouguet state: tests/core/test_jwl.cpp) lit by a plane through
// `plane_point`, a J2 steel for the plates it drives, and Steinberg's water. Units: mm, ms, g,
// MPa.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace afemp::test {

// A Gurney case: prints it and checks the driven velocity v within 10 % of Gurney's and the
// energy balance (the chemical energy released booked as a source) within 3 %.
inline void expect_gurney(const char* what, double mass_ratio, double v, double gurney,
                          double balance) {
  std::printf("%s, M/C = %.3f: %.1f m/s, Gurney %.1f m/s (%+.1f %%); energy balance %+.2f %%\n",
              what, mass_ratio, v, gurney, 100.0 * (v / gurney - 1.0), 100.0 * balance);
  EXPECT_NEAR(v, gurney, 0.10 * gurney) << what;
  EXPECT_LT(std::abs(balance), 0.03) << what;
}

inline std::string tnt_material() {
  return R"(
[materials.tnt]
density = 1.63e-3
strength = { model = "fluid" }
eos = { model = "jwl", A = 3.712e5, B = 3.231e3, R1 = 4.15, R2 = 0.95, omega = 0.30, E0 = 7.0e3 }
burn = { D = 6930, pcj = 2.1e4 }
)";
}

// Water: Steinberg's Mie-Grueneisen set (c0 1647 m/s, s 1.921, Gamma0 0.28), a fluid; the
// caller adds keys to the table (a pressure_cutoff) after it.
inline std::string water_material(const std::string& name = "water") {
  return "\n[materials." + name + R"(]
density = 1.0e-3
strength = { model = "fluid" }
eos = { model = "mie-gruneisen", c0 = 1647, s = 1.921, gamma0 = 0.28 }
)";
}

inline std::string plane_detonation(double z) {
  return "\n[[detonations]]\nplane = { point = [0, 0, " + std::to_string(z) +
         "], normal = [0, 0, 1] }\n";
}

inline std::string steel_plate_material() {
  return R"(
[materials.steel]
density = 7.85e-3
E = 200e3
nu = 0.3
strength = { model = "j2", yield = 1000 }
)";
}

// A column 0.5 mm square, held laterally, from z_min to z_max, with outflow faces at its ends:
// the [run], [grid] and [mpm] sections of the sandwich tests. USAVG: MUSL loses 6-12 % of the
// energy in the products' fast expansion (docs/explosives.md).
inline std::string sandwich_column(double end_time, double z_min, double z_max, bool splitting) {
  return "[run]\nend_time = " + std::to_string(end_time) + "\n[grid]\ncell = 0.25\nmin = [0, 0, " +
         std::to_string(z_min) + "]\nmax = [0.5, 0.5, " + std::to_string(z_max) +
         "]\nboundary = { xmin = \"symmetric\", xmax = \"symmetric\", ymin = \"symmetric\", "
         "ymax = \"symmetric\", zmin = \"outflow\", zmax = \"outflow\" }\n[mpm]\nscheme = "
         "\"USAVG\"\n" +
         (splitting ? "splitting = {}\n" : "");
}

// An eighth of a sphere of radius 5 mm of `inner` in water, on a 15 mm grid of 1 mm cells whose
// outer faces open onto water at 10 MPa. Units mm, ms, g, MPa.
inline std::string sphere_in_water(const std::string& inner_material,
                                   const std::string& inner_keys) {
  return R"(
[run]
end_time = 1.0
[grid]
cell = 1.0
min = [0, 0, 0]
max = [15, 15, 15]
boundary = { xmin = "symmetric", ymin = "symmetric", zmin = "symmetric", xmax = "absorbing", ymax = "absorbing", zmax = "absorbing" }
far_field = { centre = [0, 0, 0], pressure = 10.0 }
[mpm]
scheme = "USAVG"
[materials.gas]
density = 1.0e-5
strength = { model = "fluid" }
eos = { model = "linear-polynomial", C4 = 0.4, C5 = 0.4 }
)" + water_material() +
         R"(
[[bodies]]
name = "inner"
material = ")" +
         inner_material + R"("
shape = { sphere = { centre = [0, 0, 0], radius = 5 } }
)" + inner_keys +
         R"(
[[bodies]]
name = "water"
material = "water"
shape = { box = { min = [0, 0, 0], max = [15, 15, 15] } }
outside = ["inner"]
particles_per_cell = 1
pressure = 10.0
[[contact]]
bodies = ["inner", "water"]
method = "weld"
)";
}

}  // namespace afemp::test
